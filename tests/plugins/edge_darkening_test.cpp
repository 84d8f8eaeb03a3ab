// Headless tests of the `edge_darkening` node against reference/edge_darkening.h: random
// and stepped images with and without a control map, a constant image bit-exact, darker at
// edges than in flat areas, grazing angles darken more, 1x1, NaN stays put.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "aquarelle/reference/edge_darkening.h"
#include "support/harness.h"

namespace {

using aq::ImageF;
using aq::reference::EdgeDarkeningParams;

// resolution 1: the blur on every pixel, what reference::blur_difference_darkening computes.
aq::Result<ImageF> run(const ImageF& image, const ImageF* source, const ImageF* control,
                       const EdgeDarkeningParams& p, const char* precision = "float",
                       int resolution = 1) {
  std::map<std::string, ImageF> inputs{{"image", image}};
  if (source) inputs["source"] = *source;
  if (control) inputs["control"] = *control;
  aq::test::RenderOptions options;
  options.precision = precision;
  return aq::test::run_node("edge_darkening", inputs,
                            {{"sigma", p.sigma},
                             {"strength", p.strength},
                             {"grazing", p.grazing},
                             {"max_exponent", p.max_exponent},
                             {"resolution", resolution}},
                            options);
}

ImageF step_image(int w, int h) {
  ImageF image(w, h, 4, 1.0f);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x)
      for (int c = 0; c < 3; ++c) image.at(x, y, c) = x < w / 2 ? 0.8f : 0.3f + 0.1f * c;
  return image;
}

TEST(EdgeDarkening, MatchesReference) {
  const ImageF image = aq::test::random_image(48, 40, 11);
  const ImageF source = aq::test::random_image(48, 40, 12);
  const ImageF control = aq::test::random_image(48, 40, 13);
  const EdgeDarkeningParams p;
  for (int variant = 0; variant < 3; ++variant) {
    const ImageF* s = variant >= 1 ? &source : nullptr;
    const ImageF* c = variant == 2 ? &control : nullptr;
    const ImageF expected = aq::reference::blur_difference_darkening(image, s, c, p);
    auto got = run(image, s, c, p);
    ASSERT_TRUE(got.ok()) << got.message();
    const double error = aq::test::max_abs_diff(*got, expected);
    // The shared Gaussian truncates at 4 sigma (6.4e-5 of the range per pass); pow amplifies it
    // by k · C^(1+kd) |ln C| < 2 for these values.
    EXPECT_LE(error, 4e-4) << "variant " << variant;
    auto half = run(image, s, c, p, "half");
    ASSERT_TRUE(half.ok()) << half.message();
    EXPECT_LE(aq::test::max_abs_diff(*half, expected), 3e-3);
    std::printf("[edge_darkening] variant %d float max abs %.3g, PSNR %.1f dB\n", variant, error,
                aq::test::psnr(*got, expected));
  }
}

TEST(EdgeDarkening, ConstantImageIsBitExactIdentity) {
  for (const char* precision : {"float", "half"}) {
    const ImageF image = aq::test::constant_image(40, 30, 0.25f, 0.5f, 0.875f, 0.5f);
    auto got = run(image, nullptr, nullptr, {}, precision);
    ASSERT_TRUE(got.ok()) << got.message();
    EXPECT_EQ(aq::test::max_abs_diff(*got, image), 0.0) << precision;
  }
}

TEST(EdgeDarkening, DarkensEdgesOnlyAndMoreAtGrazingAngles) {
  const ImageF image = step_image(64, 16);
  auto got = run(image, nullptr, nullptr, {});
  ASSERT_TRUE(got.ok()) << got.message();
  EXPECT_LT(got->at(31, 8, 0), image.at(31, 8, 0) - 0.01f);  // beside the step
  EXPECT_EQ(got->at(2, 8, 0), image.at(2, 8, 0));            // flat, far from it
  ImageF facing = aq::test::constant_image(64, 16, 0.0f, 1.0f, 0.0f);
  ImageF grazing = aq::test::constant_image(64, 16, 0.0f, 1.0f, 1.0f);
  auto a = run(image, nullptr, &facing, {});
  auto b = run(image, nullptr, &grazing, {});
  ASSERT_TRUE(a.ok() && b.ok());
  EXPECT_LT(b->at(31, 8, 0), a->at(31, 8, 0));
  ImageF none = aq::test::constant_image(64, 16, 0.0f, 0.0f, 0.0f);
  auto c = run(image, nullptr, &none, {});
  ASSERT_TRUE(c.ok());
  EXPECT_EQ(aq::test::max_abs_diff(*c, image), 0.0);  // edge amount 0: untouched
}

TEST(EdgeDarkening, OnePixelAndNaN) {
  const ImageF one = aq::test::constant_image(1, 1, 0.2f, 0.4f, 0.6f);
  auto got = run(one, nullptr, nullptr, {});
  ASSERT_TRUE(got.ok()) << got.message();
  EXPECT_EQ(aq::test::max_abs_diff(*got, one), 0.0);
  ImageF image = step_image(32, 32);
  image.at(10, 10, 1) = std::numeric_limits<float>::quiet_NaN();
  auto nan = run(image, nullptr, nullptr, {});
  ASSERT_TRUE(nan.ok()) << nan.message();
  int non_finite = 0;
  for (int y = 0; y < 32; ++y)
    for (int x = 0; x < 32; ++x)
      for (int c = 0; c < 4; ++c) non_finite += std::isfinite(nan->at(x, y, c)) ? 0 : 1;
  EXPECT_EQ(non_finite, 1);
}

// Thin geometry (issue 35): a windmill sail two pixels wide, on a darker hill, its one-pixel
// side faces seen edge-on (grazing 1 in the control map), edge amount 1.5 (the FBM's high end).
// Unbounded, the exponent reached k·d ≈ 3 along the sail and at its corners: aliased dark lines
// and blots (0.9 → 0.7). The saturating exponent keeps every pixel at or above C², and the
// grazing read through a tent no longer paints a one-pixel line darker than the sail beside it.
TEST(EdgeDarkening, ThinGeometryGetsNoBlotsOrAliasedLines) {
  const int w = 64, h = 64;
  ImageF image = aq::test::constant_image(w, h, 0.55f, 0.6f, 0.45f);
  ImageF control = aq::test::constant_image(w, h, 0.0f, 1.0f, 0.0f, 0.0f);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const int across = x - y;  // a diagonal bar: |across| <= 1 is the sail
      if (std::abs(across) <= 1 && x > 8 && x < 56) {
        for (int c = 0; c < 3; ++c) image.at(x, y, c) = 0.9f;
        control.at(x, y, 1) = 1.5f;
        control.at(x, y, 2) = across == 1 ? 1.0f : 0.1f;  // one side face, edge-on
      }
    }
  const EdgeDarkeningParams p;  // defaults: sigma 3, strength 4, grazing 1, max_exponent 1
  auto got = run(image, nullptr, &control, p);
  ASSERT_TRUE(got.ok()) << got.message();
  int below_square = 0;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x)
      for (int c = 0; c < 3; ++c) {
        const double v = image.at(x, y, c);
        below_square += got->at(x, y, c) < v * v - 1e-4 ? 1 : 0;
      }
  EXPECT_EQ(below_square, 0) << "pixels darkened past C^2 (blots)";
  // Along the middle of the sail, the edge-on side (across = 1) is not much darker than the
  // sail's centre line (across = 0): no one-pixel dark line.
  double line = 0.0, centre = 0.0;
  for (int x = 20; x < 44; ++x) {
    line += got->at(x, x - 1, 0);
    centre += got->at(x, x, 0);
  }
  EXPECT_GT(line / 24.0, centre / 24.0 - 0.08) << "a dark aliased line along the sail";
  const ImageF expected = aq::reference::blur_difference_darkening(image, nullptr, &control, p);
  EXPECT_LE(aq::test::max_abs_diff(*got, expected), 4e-4);
}

// The default blurs on 2x2 cells (σ narrowed by what the averaging and the bilinear read-back
// add): close to the exact blur on a painted-like image, and a constant image is still exact.
TEST(EdgeDarkening, BlurOnCellsStaysCloseToTheExactOne) {
  const ImageF image = step_image(96, 64);
  ImageF source = image;
  for (int y = 20; y < 40; ++y)
    for (int x = 10; x < 30; ++x) source.at(x, y, 1) = 0.2f;  // a block of another colour
  const EdgeDarkeningParams p;
  auto exact = run(image, &source, nullptr, p, "float", 1);
  auto cells = run(image, &source, nullptr, p, "float", 2);
  ASSERT_TRUE(exact.ok() && cells.ok()) << exact.message() << cells.message();
  const double max = aq::test::max_abs_diff(*cells, *exact);
  const double mean = aq::test::mean_abs_diff(*cells, *exact);
  std::printf("[edge_darkening] 2x2 cells against every pixel: max %.3g, mean %.3g\n", max, mean);
  EXPECT_LE(mean, 2e-3);
  EXPECT_LE(max, 0.03);
  const ImageF flat = aq::test::constant_image(40, 30, 0.25f, 0.5f, 0.875f, 0.5f);
  auto same = run(flat, nullptr, nullptr, p, "half", 2);
  ASSERT_TRUE(same.ok());
  EXPECT_EQ(aq::test::max_abs_diff(*same, flat), 0.0);
}

}  // namespace
