// Headless tests of the `wobble` node against the double-precision reference
// (reference/wobble.h): strength 0 is the identity, a connected paper and the procedural
// paper both match the reference, lookups clamp at the borders (no value from outside the
// image, whatever the strength), the displacement does not change with resolution, and a paper
// holding NaN leaves the image finite.
#include <gtest/gtest.h>

#include <cstdlib>

#include "aquarelle/reference/wobble.h"
#include "support/harness.h"

#include <cmath>
#include <cstdio>
#include <limits>
#include <map>
#include <string>

namespace {

using aq::ImageF;

constexpr double kPi = 3.14159265358979323846;

// A smooth colourful image, so that bilinear lookups have small, predictable errors.
ImageF smooth_image(int width, int height) {
  ImageF image(width, height, 4, 1.0f);
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) {
      const double u = (x + 0.5) / width;
      const double v = (y + 0.5) / height;
      image.at(x, y, 0) = static_cast<float>(0.5 + 0.4 * std::sin(2 * kPi * (u + 0.3 * v)));
      image.at(x, y, 1) = static_cast<float>(0.5 + 0.4 * std::cos(2 * kPi * 1.5 * v));
      image.at(x, y, 2) = static_cast<float>(u * v);
    }
  }
  return image;
}

// Paper height 0.5 + 0.5 sin(2π·3u) cos(2π·2v): smooth, slopes up to ~0.3 per paper pixel.
ImageF wavy_paper(int width, int height) {
  ImageF paper(width, height, 4, 1.0f);
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) {
      const double u = (x + 0.5) / width;
      const double v = (y + 0.5) / height;
      const float h =
          static_cast<float>(0.5 + 0.5 * std::sin(2 * kPi * 3 * u) * std::cos(2 * kPi * 2 * v));
      for (int c = 0; c < 3; ++c) paper.at(x, y, c) = h;
    }
  }
  return paper;
}

aq::test::RenderOptions options_for(const ImageF& image, const std::string& precision) {
  aq::test::RenderOptions options;
  options.width = image.width;
  options.height = image.height;
  options.precision = precision;
  return options;
}

TEST(Wobble, StrengthZeroIsIdentity) {
  const ImageF input = aq::test::random_image(64, 48, 9);
  for (const char* precision : {"float", "half"}) {
    auto procedural = aq::test::run_node("wobble", {{"image", input}}, {{"strength", 0.0}},
                                         options_for(input, precision));
    ASSERT_TRUE(procedural.ok()) << procedural.message();
    EXPECT_EQ(aq::test::max_abs_diff(*procedural, input), 0.0) << precision;
    auto with_paper =
        aq::test::run_node("wobble", {{"image", input}, {"paper", wavy_paper(32, 32)}},
                           {{"strength", 0.0}}, options_for(input, precision));
    ASSERT_TRUE(with_paper.ok()) << with_paper.message();
    EXPECT_EQ(aq::test::max_abs_diff(*with_paper, input), 0.0) << precision;
  }
}

struct ReferenceCase {
  std::string precision;
  double strength;
  double max_error;
  double min_psnr;
};
class WobbleReference : public ::testing::TestWithParam<ReferenceCase> {};

// The paper (48×40) is smaller than the image (64×64) and stretched over it.
TEST_P(WobbleReference, PaperInputMatchesReference) {
  const ReferenceCase& c = GetParam();
  const ImageF input = smooth_image(64, 64);
  const ImageF paper = wavy_paper(48, 40);
  auto out = aq::test::run_node("wobble", {{"image", input}, {"paper", paper}},
                                {{"strength", c.strength}}, options_for(input, c.precision));
  ASSERT_TRUE(out.ok()) << out.message();
  const ImageF expected = aq::reference::wobble(input, paper, c.strength);
  const double error = aq::test::max_abs_diff(*out, expected);
  const double psnr = aq::test::psnr(*out, expected);
  EXPECT_LE(error, c.max_error);
  EXPECT_GE(psnr, c.min_psnr);
  // The wobble must actually move things at this strength.
  EXPECT_GT(aq::test::max_abs_diff(expected, input), 0.02);
  RecordProperty("max_abs_error", std::to_string(error));
  RecordProperty("psnr_db", std::to_string(psnr));
}

// Measured on llvmpipe: float max error < 1e-6 (≈150 dB), half 4.9e-4 (≈75 dB, the RGBA16F
// rounding of the output). The float bound leaves room for GPUs whose bilinear weights have
// 8 fractional bits.
INSTANTIATE_TEST_SUITE_P(Sweep, WobbleReference,
                         ::testing::Values(ReferenceCase{"float", 2.0, 1e-4, 90.0},
                                           ReferenceCase{"float", 8.0, 1e-4, 90.0},
                                           ReferenceCase{"float", 32.0, 1e-4, 90.0},
                                           ReferenceCase{"half", 2.0, 1e-3, 70.0},
                                           ReferenceCase{"half", 8.0, 1e-3, 70.0},
                                           ReferenceCase{"half", 32.0, 1e-3, 70.0}));

TEST(Wobble, ProceduralPaperMatchesReference) {
  const ImageF input = smooth_image(64, 64);
  const int lines = 64;
  const double grain = 4.0;
  const double strength = 8.0;
  for (int seed : {0, 3}) {
    auto out = aq::test::run_node(
        "wobble", {{"image", input}},
        {{"strength", strength}, {"paper_resolution", lines}, {"grain", grain}, {"seed", seed}},
        options_for(input, "float"));
    ASSERT_TRUE(out.ok()) << out.message();
    const ImageF paper = aq::reference::procedural_paper(
        aq::reference::procedural_paper_columns(64, 64, lines), lines, grain, seed);
    const ImageF expected = aq::reference::wobble(input, paper, strength);
    const double error = aq::test::max_abs_diff(*out, expected);
    const double psnr = aq::test::psnr(*out, expected);
    EXPECT_LE(error, 1e-4) << "seed " << seed;
    EXPECT_GE(psnr, 90.0) << "seed " << seed;
    RecordProperty("max_abs_error_seed_" + std::to_string(seed), std::to_string(error));
    RecordProperty("psnr_db_seed_" + std::to_string(seed), std::to_string(psnr));
  }
}

// A steep paper and the largest strength throw lookups far past the borders: with clamping every
// output value is a blend of image values (here all in [0.25, 0.75]) and matches the clamping
// reference; wrapping or a border colour would not.
TEST(Wobble, LookupsNeverLeaveTheImage) {
  ImageF input = aq::test::random_image(40, 40, 5, 0.25f, 0.75f);
  ImageF paper(8, 8, 4, 1.0f);
  for (int y = 0; y < 8; ++y) {
    for (int x = 0; x < 8; ++x) {
      for (int c = 0; c < 3; ++c) paper.at(x, y, c) = static_cast<float>((x + y) % 2);
    }
  }
  auto out = aq::test::run_node("wobble", {{"image", input}, {"paper", paper}},
                                {{"strength", 64.0}}, options_for(input, "float"));
  ASSERT_TRUE(out.ok()) << out.message();
  ASSERT_TRUE(aq::test::all_finite(*out));
  for (size_t i = 0; i < out->pixels.size(); ++i) {
    if (i % 4 == 3) continue;
    ASSERT_GE(out->pixels[i], 0.25f - 1e-6f) << i;
    ASSERT_LE(out->pixels[i], 0.75f + 1e-6f) << i;
  }
  const ImageF expected = aq::reference::wobble(input, paper, 64.0);
  const double error = aq::test::mean_abs_diff(*out, expected);
  EXPECT_LE(error, 1e-4);
  RecordProperty("mean_abs_error", std::to_string(error));
}

// The procedural paper has a fixed number of paper pixels across the image, so the same
// displacement (in uv) appears at 64×64 and 128×128: averaging 2×2 blocks of the large render
// gives the small one up to sampling differences, although the wobble itself moves values a lot.
TEST(Wobble, DisplacementDoesNotChangeWithResolution) {
  const nlohmann::json params = {
      {"strength", 64.0}, {"paper_resolution", 128}, {"grain", 16.0}, {"seed", 1}};
  const ImageF small_input = smooth_image(64, 64);
  const ImageF large_input = smooth_image(128, 128);
  auto small = aq::test::run_node("wobble", {{"image", small_input}}, params,
                                  options_for(small_input, "float"));
  auto large = aq::test::run_node("wobble", {{"image", large_input}}, params,
                                  options_for(large_input, "float"));
  ASSERT_TRUE(small.ok()) << small.message();
  ASSERT_TRUE(large.ok()) << large.message();
  ImageF reduced(64, 64, 4);
  for (int y = 0; y < 64; ++y) {
    for (int x = 0; x < 64; ++x) {
      for (int c = 0; c < 4; ++c) {
        reduced.at(x, y, c) =
            0.25f * (large->at(2 * x, 2 * y, c) + large->at(2 * x + 1, 2 * y, c) +
                     large->at(2 * x, 2 * y + 1, c) + large->at(2 * x + 1, 2 * y + 1, c));
      }
    }
  }
  const double moved = aq::test::mean_abs_diff(*small, small_input, 3);
  const double mismatch = aq::test::mean_abs_diff(*small, reduced, 3);
  EXPECT_GT(moved, 0.01);
  EXPECT_LT(mismatch, moved / 4.0);
  RecordProperty("moved", std::to_string(moved));
  RecordProperty("mismatch", std::to_string(mismatch));
}

TEST(Wobble, NonFinitePaperKeepsTheImageFinite) {
  const ImageF input = aq::test::random_image(32, 32, 2);
  ImageF paper = wavy_paper(32, 32);
  paper.at(10, 10, 0) = std::numeric_limits<float>::quiet_NaN();
  paper.at(20, 5, 0) = std::numeric_limits<float>::infinity();
  auto out = aq::test::run_node("wobble", {{"image", input}, {"paper", paper}}, {{"strength", 8.0}},
                                options_for(input, "float"));
  ASSERT_TRUE(out.ok()) << out.message();
  EXPECT_TRUE(aq::test::all_finite(*out));
}

TEST(Wobble, OnePixelImageAndPaper) {
  const ImageF input = aq::test::constant_image(1, 1, 0.2f, 0.4f, 0.6f, 1.0f);
  for (bool with_paper : {false, true}) {
    std::map<std::string, ImageF> inputs = {{"image", input}};
    if (with_paper) inputs["paper"] = aq::test::constant_image(1, 1, 0.7f, 0.7f, 0.7f, 1.0f);
    auto out = aq::test::run_node("wobble", inputs, {{"strength", 64.0}, {"paper_resolution", 8}},
                                  options_for(input, "float"));
    ASSERT_TRUE(out.ok()) << out.message();
    EXPECT_EQ(aq::test::max_abs_diff(*out, input), 0.0) << with_paper;
  }
}

}  // namespace

namespace {

// image -> wobble, its paper from a `paper` node, optionally with the paper's gradient.
std::string paper_wobble_graph(bool gradient, int paper_width) {
  nlohmann::json inputs = {{"image", "input.image"}, {"paper", "paper.image"}};
  if (gradient) inputs["gradient"] = "paper.gradient";
  nlohmann::json graph = {
      {"aquarelle", 1},
      {"nodes",
       {{"input", {{"type", "image_input"}, {"params", {{"name", "image"}}}}},
        {"paper",
         {{"type", "paper"},
          {"params", {{"grain_scale", 12}, {"width", paper_width}, {"height", 0}}}}},
        {"wobble", {{"type", "wobble"}, {"params", {{"strength", 24.0}}}, {"inputs", inputs}}}}},
      {"output", "wobble.image"}};
  return graph.dump();
}

}  // namespace

// The paper's precomputed gradient gives the image wobble gets by differencing the height
// itself (shifting by one texel commutes with bilinear filtering), except within a texel of the
// border, where the clamp comes before instead of after the difference.
// Both sides with the paper at full precision: with formats by need on, the paper that only
// wobble.paper reads is stored in 8 bits (see the next test).
TEST(Wobble, PrecomputedPaperGradientEqualsTheDifferences) {
  const ImageF input = aq::test::random_image(96, 64, 41);
  setenv("AQUARELLE_FORMATS_BY_NEED", "0", 1);
  for (int paper_width : {0, 61}) {  // the image's size, and another size (filtered reads)
    aq::test::RenderOptions options;
    options.width = 96;
    options.height = 64;
    auto with =
        aq::test::render_graph(paper_wobble_graph(true, paper_width), options, {{"image", input}});
    auto without =
        aq::test::render_graph(paper_wobble_graph(false, paper_width), options, {{"image", input}});
    ASSERT_TRUE(with.ok()) << with.message();
    ASSERT_TRUE(without.ok()) << without.message();
    double inside = 0.0;
    for (int y = 2; y < 62; ++y)
      for (int x = 2; x < 94; ++x)
        for (int c = 0; c < 4; ++c)
          inside = std::max<double>(inside, std::abs(with->at(x, y, c) - without->at(x, y, c)));
    EXPECT_LE(inside, 1e-5) << "paper width " << paper_width;
    std::printf("[wobble gradient] paper width %d: max difference inside %.3g\n", paper_width,
                inside);
    EXPECT_GT(aq::test::max_abs_diff(*without, input), 0.05) << "the wobble moved nothing";
  }
  unsetenv("AQUARELLE_FORMATS_BY_NEED");
}

// Formats by need: wobble.paper is content with 8 bits, so without the precomputed gradient
// wobble differences 8-bit heights. The slope then moves by at most 1/510 per paper pixel (plus
// llvmpipe's 8-bit filter weights between texels, allowed for by the factor 1.25), the lookup
// by strength/510 paper pixels, and an image whose values change by at most 1 per pixel (this
// random one) by that many image pixels. Measured at strength 24: 0.044 (paper of the image's
// size), 0.083 (61 paper pixels across 96).
TEST(Wobble, DifferencesOfAn8BitPaperStayWithinTheQuantisationBound) {
  const ImageF input = aq::test::random_image(96, 64, 41);
  const double strength = 24.0;
  for (int paper_width : {0, 61}) {
    aq::test::RenderOptions options;
    options.width = 96;
    options.height = 64;
    auto precomputed =
        aq::test::render_graph(paper_wobble_graph(true, paper_width), options, {{"image", input}});
    auto differenced =
        aq::test::render_graph(paper_wobble_graph(false, paper_width), options, {{"image", input}});
    ASSERT_TRUE(precomputed.ok()) << precomputed.message();
    ASSERT_TRUE(differenced.ok()) << differenced.message();
    const double image_pixels_per_paper_pixel = paper_width == 0 ? 1.0 : 96.0 / paper_width;
    const double bound = 1.25 * strength / 510.0 * image_pixels_per_paper_pixel;
    double inside = 0.0;
    for (int y = 2; y < 62; ++y)
      for (int x = 2; x < 94; ++x)
        for (int c = 0; c < 4; ++c)
          inside = std::max<double>(inside,
                                    std::abs(precomputed->at(x, y, c) - differenced->at(x, y, c)));
    EXPECT_LE(inside, bound) << "paper width " << paper_width;
    EXPECT_GT(inside, 1e-5) << "paper width " << paper_width << ": the paper was not 8-bit";
  }
}
