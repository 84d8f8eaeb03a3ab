// EGL and OSMesa give the same image for the same graph (DESIGN.md: "EGL and OSMesa agree
// within a stated tolerance": 1e-3 here, in half precision).
#include <gtest/gtest.h>

#include "support/harness.h"

namespace aq::test {
namespace {

TEST(Backends, EglAndOsmesaAgree) {
  const char* graph = R"({
    "aquarelle": 1,
    "nodes": {
      "src": {"type": "image_input", "params": {"name": "image"}},
      "tint": {"type": "tint", "params": {"amount": 0.4}, "inputs": {"image": "src.image"}},
      "vig": {"type": "vignette", "inputs": {"image": "tint.image"}}
    },
    "output": "vig.image"
  })";
  ImageF input = gradient_image(48, 32);
  RenderOptions options;
  options.width = 48;
  options.height = 32;
  options.precision = "half";
  options.gl = "egl";
  auto egl = render_graph(graph, options, {{"image", input}});
  ASSERT_TRUE(egl.ok()) << egl.message();
  options.gl = "osmesa";
  auto osmesa = render_graph(graph, options, {{"image", input}});
  ASSERT_TRUE(osmesa.ok()) << osmesa.message();
  EXPECT_LE(max_abs_diff(*egl, *osmesa), 1e-3);
  EXPECT_GT(max_abs_diff(*egl, input), 0.05) << "the graph did change the image";
}

TEST(Backends, InterleavedBackendsKeepWorking) {
  ImageF input = random_image(24, 16, 3);
  RenderOptions options;
  options.width = 24;
  options.height = 16;
  std::optional<ImageF> first;
  for (int round = 0; round < 3; ++round) {
    for (const char* gl : {"egl", "osmesa", "egl", "egl", "osmesa"}) {
      options.gl = gl;
      auto out = run_node("tint", {{"image", input}}, {{"amount", 0.25 + 0.1 * round}}, options);
      ASSERT_TRUE(out.ok()) << gl << " round " << round << ": " << out.message();
      auto vignette = run_node("vignette", {{"image", *out}}, nlohmann::json::object(), options);
      ASSERT_TRUE(vignette.ok()) << gl << " round " << round << ": " << vignette.message();
      auto blur = run_node("blur", {{"image", *out}}, {{"sigma", 2.0}}, options);
      ASSERT_TRUE(blur.ok()) << gl << " round " << round << ": " << blur.message();
    }
  }
}

TEST(Backends, SameGraphSameImageRunAfterRun) {
  ImageF input = random_image(32, 32, 7);
  RenderOptions options;
  options.width = 32;
  options.height = 32;
  auto first = run_node("tint", {{"image", input}}, {{"amount", 0.3}}, options);
  auto second = run_node("tint", {{"image", input}}, {{"amount", 0.3}}, options);
  ASSERT_TRUE(first.ok() && second.ok());
  EXPECT_EQ(max_abs_diff(*first, *second), 0.0);
}

}  // namespace
}  // namespace aq::test
