// Golden frames: frames 1 and 24 of graphs/underwater.json at 160x90 must still look as they
// did when scripts/update-golden.sh last made them (a change to the picture is then deliberate
// and explained in its commit). Like idiff: most pixels within a tight bound, a few outliers
// allowed for rasterisation differences, and the mean error small.
#include <gtest/gtest.h>

#include <aquarelle/core/color.h>
#include <aquarelle/core/image_io.h>

#include <cmath>

#include "support/harness.h"

namespace aq::test {
namespace {

class Golden : public ::testing::TestWithParam<std::tuple<int, std::string>> {};

TEST_P(Golden, MatchesTheCommittedFrame) {
  auto [frame, gl] = GetParam();
  auto config = ColorConfig::load();
  ASSERT_TRUE(config.ok()) << config.message();
  auto golden = read_image(source_path("tests/golden/underwater_" + std::to_string(frame) + ".exr"),
                           *config);
  ASSERT_TRUE(golden.ok()) << golden.message();
  RenderOptions options;
  options.width = 160;
  options.height = 90;
  options.frame = frame;
  options.precision = "float";
  options.gl = gl;
  auto rendered = render_graph_file(source_path("graphs/underwater.json"), options);
  ASSERT_TRUE(rendered.ok()) << rendered.message();
  ASSERT_EQ(rendered->width, golden->width);
  ASSERT_EQ(rendered->height, golden->height);
  int outliers = 0;
  for (int y = 0; y < golden->height; ++y) {
    for (int x = 0; x < golden->width; ++x) {
      for (int c = 0; c < 3; ++c) {
        if (std::abs(rendered->at(x, y, c) - golden->at(x, y, c)) > 0.02f) {
          ++outliers;
          break;
        }
      }
    }
  }
  EXPECT_LE(outliers, golden->width * golden->height / 200) << "more than 0.5% of pixels differ";
  EXPECT_LE(mean_abs_diff(*rendered, *golden, 3), 2e-3);
}

INSTANTIATE_TEST_SUITE_P(Frames, Golden,
                         ::testing::Combine(::testing::Values(1, 24),
                                            ::testing::Values("egl", "osmesa")));

}  // namespace
}  // namespace aq::test
