// A test fixture that owns a headless GL context of its own (EGL, else OSMesa), current for the
// test's body, for tests of host pieces that make GL objects without an evaluator (the texture
// pool, the shader cache).
#pragma once

#include <gtest/gtest.h>

#include <aquarelle/core/gl_context.h>

#include <memory>

namespace aq::test {

class GlContextTest : public ::testing::Test {
 protected:
  void SetUp() override {
    auto context = create_headless_context(GlBackend::kAuto);
    ASSERT_TRUE(context.ok()) << context.message();
    context_ = std::move(*context);
    context_->activate();
  }

  std::unique_ptr<GlContext> context_;
};

}  // namespace aq::test
