// Proxy renders (quality presets below final): nodes render at the graph's size times the
// render scale, parameters in pixels mean output pixels, the output comes back at the graph's
// size, and the flagship graph stays within the error docs/performance.md states.
#include <gtest/gtest.h>

#include "support/harness.h"

namespace aq::test {
namespace {

RenderOptions at(const char* quality, int width, int height) {
  RenderOptions options;
  options.width = width;
  options.height = height;
  options.quality = quality;
  options.precision = "float";
  return options;
}

TEST(ProxyRender, NodesSeeTheScaledSizeAndTheOutputComesBackAtTheGraphSize) {
  const char* graph = R"({
    "aquarelle": 1,
    "nodes": {
      "scene": {"type": "scene", "params": {"preset": "plane_box"}},
      "shadow": {"type": "shadowmap", "params": {"size": 256, "auto_size": false},
                 "inputs": {"scene": "scene.scene"}},
      "noise": {"type": "noise", "params": {"scale": 4}}
    },
    "output": "noise.image"
  })";
  for (auto [quality, scale] :
       {std::pair{"final", 1.0}, std::pair{"preview", 0.5}, std::pair{"draft", 0.25}}) {
    auto noise = render_graph(graph, at(quality, 96, 64));
    ASSERT_TRUE(noise.ok()) << noise.message();
    EXPECT_EQ(noise->width, 96) << quality;  // resampled back to the graph's size
    EXPECT_EQ(noise->height, 64) << quality;
    RenderOptions options = at(quality, 96, 64);
    options.output = "shadow.depth";
    auto shadow = render_graph(graph, options);
    ASSERT_TRUE(shadow.ok()) << shadow.message();
    // Not the working size, so not resampled: the map's own size, scaled like the screen.
    EXPECT_EQ(shadow->width, static_cast<int>(256 * scale)) << quality;
  }
}

// A blur's sigma is in output pixels: the proxy blur at half size with sigma/2 working pixels
// matches the full render far better than one that took sigma as working pixels.
TEST(ProxyRender, PixelParametersMeanOutputPixels) {
  auto graph = [](double sigma) {
    return R"({"aquarelle": 1, "nodes": {
      "noise": {"type": "noise", "params": {"scale": 16}},
      "blur": {"type": "blur", "params": {"sigma": )" +
           std::to_string(sigma) + R"(, "depth_weight": 1.0, "radial_weight": 0.0},
               "inputs": {"image": "noise.image"}}},
      "output": "blur.image"})";
  };
  auto full = render_graph(graph(6.0), at("final", 192, 128));
  auto proxy = render_graph(graph(6.0), at("preview", 192, 128));
  auto proxy_unscaled = render_graph(graph(12.0), at("preview", 192, 128));
  ASSERT_TRUE(full.ok() && proxy.ok() && proxy_unscaled.ok());
  const double scaled_error = mean_abs_diff(*proxy, *full, 3);
  const double unscaled_error = mean_abs_diff(*proxy_unscaled, *full, 3);
  EXPECT_LT(scaled_error, 0.5 * unscaled_error)
      << "scaled " << scaled_error << ", unscaled " << unscaled_error;
}

// The documented cost of the presets: preview and draft against the full-size render of the
// flagship graph (docs/performance.md gives the figures at 1280x720 against the reference).
TEST(ProxyRender, UnderwaterPresetsStayWithinTheirStatedError) {
  const std::string path = source_path("graphs/underwater.json");
  auto full = render_graph_file(path, at("final", 320, 180));
  auto preview = render_graph_file(path, at("preview", 320, 180));
  auto draft = render_graph_file(path, at("draft", 320, 180));
  ASSERT_TRUE(full.ok() && preview.ok() && draft.ok());
  const double preview_error = mean_abs_diff(*preview, *full, 3);
  const double draft_error = mean_abs_diff(*draft, *full, 3);
  std::printf("underwater 320x180 vs final: preview mean abs %.4f, draft %.4f\n", preview_error,
              draft_error);
  EXPECT_LT(preview_error, 0.05);
  EXPECT_LT(draft_error, 0.08);
  EXPECT_LT(preview_error, draft_error) << "a larger scale is closer to the full render";
  EXPECT_GT(preview_error, 0.0) << "the presets do differ from final";
}

}  // namespace
}  // namespace aq::test
