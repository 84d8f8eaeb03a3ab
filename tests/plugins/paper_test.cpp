// Headless tests of the `paper` texture node against the CPU reference
// (reference/paper_reference.h): float and half precision, flat paper at roughness 0,
// seamless tiling, resolution independence, seeds, range, and a parameter sweep.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>

#include "aquarelle/reference/paper_reference.h"
#include "support/harness.h"

namespace {

using aq::ImageF;
using aq::reference::PaperParams;

ImageF run(const PaperParams& p, int width, int height, const char* precision = "float") {
  aq::test::RenderOptions options;
  options.precision = precision;
  const nlohmann::json params = {{"grain_scale", p.grain_scale},
                                 {"fiber_scale", p.fiber_scale},
                                 {"octaves", p.octaves},
                                 {"fiber_weight", p.fiber_weight},
                                 {"roughness", p.roughness},
                                 {"seed", p.seed},
                                 {"width", width},
                                 {"height", height}};
  auto out = aq::test::run_node("paper", {}, params, options);
  EXPECT_TRUE(out.ok()) << (out.ok() ? "" : out.message());
  return out.ok() ? *out : ImageF();
}

PaperParams small_paper() {
  PaperParams p;
  p.grain_scale = 16;  // a 64-pixel test texture gets 4-pixel grains
  p.fiber_scale = 3;
  return p;
}

TEST(Paper, MatchesReference) {
  for (auto [w, h] : {std::pair{64, 64}, std::pair{100, 60}}) {
    const PaperParams p = small_paper();
    const ImageF expected = aq::reference::paper_texture(p, w, h);
    const ImageF got = run(p, w, h);
    ASSERT_EQ(got.width, w);
    const double err = aq::test::max_abs_diff(got, expected);
    EXPECT_LT(err, 2e-5) << w << "x" << h;
    EXPECT_GT(aq::test::psnr(got, expected), 90.0);
    RecordProperty("max_abs_float", std::to_string(err));
    const ImageF half = run(p, w, h, "half");
    // Within one RGBA16F step (2^-11 below 1; llvmpipe truncates).
    EXPECT_LT(aq::test::max_abs_diff(half, expected), 5e-4) << w << "x" << h;
  }
}

TEST(Paper, RoughnessZeroIsExactlyFlat) {
  PaperParams p = small_paper();
  p.roughness = 0.0;
  const ImageF got = run(p, 40, 30);
  ASSERT_FALSE(got.empty());
  for (int y = 0; y < got.height; ++y) {
    for (int x = 0; x < got.width; ++x) {
      for (int c = 0; c < 3; ++c) ASSERT_EQ(got.at(x, y, c), 0.5f);
      ASSERT_EQ(got.at(x, y, 3), 1.0f);
    }
  }
}

TEST(Paper, TilesSeamlessly) {
  // One pixel past each edge of the continuous height field is the opposite edge's pixel, and
  // the jump across the edge is no larger than inside the tile.
  const int n = 64;
  const PaperParams p = small_paper();
  const ImageF tile = run(p, n, n);
  ASSERT_FALSE(tile.empty());
  double worst_wrap = 0.0, edge_jump = 0.0, inner_jump = 0.0;
  for (int i = 0; i < n; ++i) {
    const double c = (i + 0.5) / n;
    worst_wrap = std::max(
        {worst_wrap,
         std::abs(aq::reference::paper_height(1.0 + 0.5 / n, c, n, n, p) - tile.at(0, i, 0)),
         std::abs(aq::reference::paper_height(c, 1.0 + 0.5 / n, n, n, p) - tile.at(i, 0, 0)),
         std::abs(aq::reference::paper_height(-0.5 / n, c, n, n, p) - tile.at(n - 1, i, 0))});
    edge_jump += std::abs(tile.at(n - 1, i, 0) - tile.at(0, i, 0)) +
                 std::abs(tile.at(i, n - 1, 0) - tile.at(i, 0, 0));
    for (int j = 0; j + 1 < n; ++j) {
      inner_jump += (std::abs(tile.at(j + 1, i, 0) - tile.at(j, i, 0)) +
                     std::abs(tile.at(i, j + 1, 0) - tile.at(i, j, 0))) /
                    (n - 1);
    }
  }
  EXPECT_LT(worst_wrap, 2e-5);
  EXPECT_LT(edge_jump, 2.0 * inner_jump);
}

TEST(Paper, IsResolutionIndependent) {
  const PaperParams p = small_paper();
  const ImageF small = run(p, 64, 64);
  const ImageF large = run(p, 192, 192);
  ASSERT_FALSE(small.empty() || large.empty());
  double worst = 0.0;
  for (int y = 0; y < 64; ++y) {
    for (int x = 0; x < 64; ++x) {
      worst =
          std::max(worst, double(std::abs(small.at(x, y, 0) - large.at(3 * x + 1, 3 * y + 1, 0))));
    }
  }
  EXPECT_LT(worst, 1e-5);
}

TEST(Paper, SameSeedIsIdenticalOtherSeedDiffers) {
  PaperParams p = small_paper();
  p.seed = 3;
  const ImageF a = run(p, 64, 64);
  const ImageF b = run(p, 64, 64);
  p.seed = 4;
  const ImageF c = run(p, 64, 64);
  EXPECT_EQ(aq::test::max_abs_diff(a, b), 0.0);
  EXPECT_GT(aq::test::mean_abs_diff(a, c, 3), 0.03);
}

TEST(Paper, TinyAndThinSizesMatchTheReference) {
  for (auto [w, h] : {std::pair{1, 1}, std::pair{3, 50}, std::pair{120, 1}}) {
    const PaperParams p = small_paper();
    const ImageF got = run(p, w, h);
    ASSERT_EQ(got.width, w);
    ASSERT_EQ(got.height, h);
    EXPECT_LT(aq::test::max_abs_diff(got, aq::reference::paper_texture(p, w, h)), 2e-5)
        << w << "x" << h;
  }
}

TEST(Paper, ParameterSweepStaysInUnitRangeAndMatchesReference) {
  for (double fiber_weight : {0.0, 0.35, 1.0}) {
    for (double roughness : {0.25, 1.0}) {
      for (int grain_scale : {1, 7, 40}) {
        PaperParams p = small_paper();
        p.fiber_weight = fiber_weight;
        p.roughness = roughness;
        p.grain_scale = grain_scale;
        const ImageF got = run(p, 48, 48);
        ASSERT_FALSE(got.empty());
        EXPECT_LT(aq::test::max_abs_diff(got, aq::reference::paper_texture(p, 48, 48)), 5e-5)
            << fiber_weight << " " << roughness << " " << grain_scale;
        for (float v : got.pixels) {
          ASSERT_GE(v, 0.0f);
          ASSERT_LE(v, 1.0f);
        }
      }
    }
  }
}

}  // namespace
