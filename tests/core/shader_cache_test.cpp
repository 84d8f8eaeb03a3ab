// The shader cache (nodes/src/shader_cache.h) answers a node's every-frame request for its
// program from the sources as given, without expanding their #includes again; these tests check
// that the shortcut never hands out the wrong program and keeps what the expansion gave:
// includes resolved, distinct variants distinct, failures reported each time, and files read
// anew under hot reload.
#include <gtest/gtest.h>

#include <cstdio>
#include <fstream>
#include <string>

#include "../../nodes/src/shader_cache.h"
#include "support/gl_context_test.h"

namespace aq {
namespace {

using ShaderCacheTest = test::GlContextTest;

constexpr const char* kRed =
    "#include \"aquarelle/hdr8.glsl\"\n"
    "out vec4 o;\n"
    "void main() { o = aq_hdr8_encode(vec4(1.0, 0.0, 0.0, 1.0)); }\n";

TEST_F(ShaderCacheTest, TheSameSourcesGiveTheSameProgramAndAnotherVariantItsOwn) {
  ShaderCache cache;
  const aq_shader_source red{"red.frag", kRed, nullptr};
  auto first = cache.program(nullptr, &red);
  ASSERT_TRUE(first.ok()) << first.message();
  // A copy of the text at another address: the same program, no second compile.
  const std::string copy = kRed;
  const aq_shader_source same{"other_name.frag", copy.c_str(), nullptr};
  auto again = cache.program(nullptr, &same);
  ASSERT_TRUE(again.ok()) << again.message();
  EXPECT_EQ(*again, *first);
  EXPECT_EQ(cache.size(), 1u);
  // A variant (one more define, as nodes prepend them) is another program.
  const std::string variant = "#define AQ_VARIANT 1\n" + copy;
  const aq_shader_source other{"red.frag", variant.c_str(), nullptr};
  auto second = cache.program(nullptr, &other);
  ASSERT_TRUE(second.ok()) << second.message();
  EXPECT_NE(*second, *first);
  EXPECT_EQ(cache.size(), 2u);
  // The vertex stage is part of the key: the same fragment text with another vertex shader.
  const aq_shader_source vertex{
      "quad.vert", "void main() { gl_Position = vec4(0.0, 0.0, 0.0, 1.0); }\n", nullptr};
  auto third = cache.program(&vertex, &red);
  ASSERT_TRUE(third.ok()) << third.message();
  EXPECT_NE(*third, *first);
  EXPECT_EQ(cache.size(), 3u);
}

TEST_F(ShaderCacheTest, AFailingShaderIsReportedWithItsFileAndLineEveryTime) {
  ShaderCache cache;
  const aq_shader_source broken{"broken.frag", "out vec4 o;\nvoid main() { o = undefined_name; }\n",
                                nullptr};
  for (int attempt = 0; attempt < 2; ++attempt) {
    auto program = cache.program(nullptr, &broken);
    ASSERT_FALSE(program.ok());
    EXPECT_NE(program.message().find("broken.frag:2"), std::string::npos) << program.message();
  }
  EXPECT_EQ(cache.size(), 0u);
}

TEST_F(ShaderCacheTest, HotReloadReadsTheFileAgainOnEveryRequest) {
  const std::string path = ::testing::TempDir() + "aquarelle_shader_cache_test.frag";
  auto write = [&](const char* colour) {
    std::ofstream file(path, std::ios::trunc);
    file << "out vec4 o;\nvoid main() { o = vec4(" << colour << "); }\n";
  };
  write("1.0, 0.0, 0.0, 1.0");
  const aq_shader_source source{"edited.frag", "out vec4 o;\nvoid main() { o = vec4(0.0); }\n",
                                path.c_str()};
  ShaderCache cache;
  cache.set_hot_reload(true);
  auto before = cache.program(nullptr, &source);
  ASSERT_TRUE(before.ok()) << before.message();
  write("0.0, 1.0, 0.0, 1.0");
  auto after = cache.program(nullptr, &source);
  ASSERT_TRUE(after.ok()) << after.message();
  EXPECT_NE(*after, *before) << "the edited file was not read again";
  // Without hot reload the embedded text counts, whatever the file holds.
  cache.set_hot_reload(false);
  auto embedded = cache.program(nullptr, &source);
  ASSERT_TRUE(embedded.ok()) << embedded.message();
  EXPECT_NE(*embedded, *after);
  EXPECT_EQ(cache.size(), 3u);
  std::remove(path.c_str());
}

}  // namespace
}  // namespace aq
