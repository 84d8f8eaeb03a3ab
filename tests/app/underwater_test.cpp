// End to end: the flagship graph renders, animates, agrees between EGL and OSMesa, and renders
// at its full 1280x720 through the command line.
#include <gtest/gtest.h>

#include <aquarelle/core/color.h>
#include <aquarelle/core/image_io.h>

#include <cmath>

#include "app/cli_support.h"
#include "support/harness.h"

namespace aq::test {
namespace {

const std::string kGraph = source_path("graphs/underwater.json");

double channel_spread(const ImageF& image) {
  double lo = 1e9, hi = -1e9;
  for (size_t i = 0; i < image.pixels.size(); i += 4) {
    double luma = 0.2126 * image.pixels[i] + 0.7152 * image.pixels[i + 1] +
                  0.0722 * image.pixels[i + 2];
    lo = std::min(lo, luma);
    hi = std::max(hi, luma);
  }
  return hi - lo;
}

TEST(Underwater, FramesOneToThreeMatchBetweenEglAndOsmesaAndAnimate) {
  RenderOptions options;
  options.width = 256;
  options.height = 144;
  options.precision = "half";
  std::vector<ImageF> egl_frames;
  for (int frame = 1; frame <= 3; ++frame) {
    options.frame = frame;
    options.gl = "egl";
    auto egl = render_graph_file(kGraph, options);
    ASSERT_TRUE(egl.ok()) << egl.message();
    options.gl = "osmesa";
    auto osmesa = render_graph_file(kGraph, options);
    ASSERT_TRUE(osmesa.ok()) << osmesa.message();
    EXPECT_TRUE(all_finite(*egl));
    // Same driver (llvmpipe) behind both: only rasterisation order may differ.
    EXPECT_LE(mean_abs_diff(*egl, *osmesa, 3), 1e-3) << "frame " << frame;
    EXPECT_GT(channel_spread(*egl), 0.2) << "a readable picture, not a uniform wash";
    egl_frames.push_back(std::move(*egl));
  }
  EXPECT_GT(max_abs_diff(egl_frames[0], egl_frames[2], 3), 0.01)
      << "the fish swims and the caustics move between frames";
}

TEST(Underwater, RendersAtFullSizeFromTheCommandLine) {
  auto dir = scratch_dir("underwater");
  auto result = aquarelle("render " + kGraph + " -q --frames 2 -o " + (dir / "uw.exr").string());
  ASSERT_EQ(result.exit_code, 0) << result.output;
  auto config = ColorConfig::load();
  ASSERT_TRUE(config.ok());
  auto image = read_image((dir / "uw.exr").string(), *config);
  ASSERT_TRUE(image.ok()) << image.message();
  EXPECT_EQ(image->width, 1280);
  EXPECT_EQ(image->height, 720);
  EXPECT_TRUE(all_finite(*image));
  EXPECT_GT(channel_spread(*image), 0.2);
}

}  // namespace
}  // namespace aq::test
