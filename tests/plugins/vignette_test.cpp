// Headless tests of the `vignette` node against the CPU reference (reference/vignette.h):
// identity cases, exactness at strength 0 and 1, aspect ratio, radius beyond the corners, and a
// parameter sweep in float and half precision.
#include <gtest/gtest.h>

#include <cmath>

#include "aquarelle/reference/vignette.h"
#include "support/harness.h"

namespace {

using aq::ImageF;
using aq::reference::VignetteParams;

nlohmann::json to_json(const VignetteParams& p) {
  return {{"radius", p.radius}, {"strength", p.strength}, {"softness", p.softness}};
}

aq::test::RenderOptions precision(const char* name) {
  aq::test::RenderOptions options;
  options.precision = name;
  return options;
}

ImageF run(const ImageF& input, const VignetteParams& params, const char* prec = "float") {
  auto out = aq::test::run_node("vignette", {{"image", input}}, to_json(params), precision(prec));
  EXPECT_TRUE(out.ok()) << (out.ok() ? "" : out.message());
  return out.ok() ? *out : ImageF();
}

TEST(Vignette, MatchesReferenceWithDefaultsOnAWideImage) {
  const ImageF input = aq::test::random_image(96, 54, 11);
  const ImageF expected = aq::reference::vignette(input);
  const ImageF got = run(input, {});
  ASSERT_FALSE(got.empty());
  const double err = aq::test::max_abs_diff(got, expected);
  EXPECT_LE(err, 1e-5);
  EXPECT_GE(aq::test::psnr(got, expected), 100.0);
  RecordProperty("max_abs_float", std::to_string(err));
}

TEST(Vignette, MatchesReferenceInHalfPrecision) {
  const ImageF input = aq::test::random_image(64, 64, 12);
  const ImageF expected = aq::reference::vignette(input);
  const ImageF got = run(input, {}, "half");
  ASSERT_FALSE(got.empty());
  // RGBA16F keeps 11 significant bits: half an ulp of values below 1 is at most 2.5e-4.
  EXPECT_LE(aq::test::max_abs_diff(got, expected), 5e-4);
  EXPECT_GE(aq::test::psnr(got, expected), 70.0);
}

TEST(Vignette, StrengthZeroIsExactIdentity) {
  const ImageF input = aq::test::random_image(40, 30, 13);
  const ImageF got = run(input, {0.45, 0.0, 1.0});
  EXPECT_EQ(aq::test::max_abs_diff(got, input), 0.0);
}

TEST(Vignette, StrengthOneWithHardEdgeIsExactlyBlackOutside) {
  const ImageF input = aq::test::constant_image(64, 64, 0.8f, 0.6f, 0.4f, 0.5f);
  const ImageF got = run(input, {0.3, 1.0, 0.0});
  ASSERT_FALSE(got.empty());
  // Corner pixel (d = 0.69) is black, alpha kept; centre pixel untouched.
  for (int c = 0; c < 3; ++c) EXPECT_EQ(got.at(0, 0, c), 0.0f);
  EXPECT_EQ(got.at(0, 0, 3), 0.5f);
  for (int c = 0; c < 4; ++c) EXPECT_EQ(got.at(32, 32, c), input.at(32, 32, c));
}

TEST(Vignette, RadiusAtOrBeyondTheCornerChangesNothing) {
  for (auto [w, h] : {std::pair{64, 64}, std::pair{128, 36}, std::pair{1, 1}, std::pair{7, 200}}) {
    const ImageF input = aq::test::random_image(w, h, 14);
    const double corner = 0.5 * std::hypot(w, h) / std::min(w, h);
    const ImageF got = run(input, {corner, 1.0, 1.0});
    EXPECT_EQ(aq::test::max_abs_diff(got, input), 0.0) << w << "x" << h;
    const ImageF beyond = run(input, {corner + 0.3, 1.0, 0.0});
    EXPECT_EQ(aq::test::max_abs_diff(beyond, input), 0.0) << w << "x" << h;
  }
}

TEST(Vignette, IsAspectCorrectCircularAndReachesTheCorners) {
  const ImageF input = aq::test::constant_image(128, 64, 1.0f, 1.0f, 1.0f);
  const ImageF got = run(input, {0.3, 0.7, 1.0});
  ASSERT_FALSE(got.empty());
  // Pixels 25 px right of and 25 px above the centre are at the same distance: same factor.
  const float right = got.at(64 + 25, 32, 0);
  const float up = got.at(64, 32 + 25, 0);
  EXPECT_LT(right, 1.0f);
  EXPECT_NEAR(right, up, 1e-6);
  // All four corners are darkened by nearly the full strength (they sit half a pixel inside).
  for (auto [x, y] : {std::pair{0, 0}, std::pair{127, 0}, std::pair{0, 63}, std::pair{127, 63}}) {
    EXPECT_NEAR(got.at(x, y, 0), 0.3f, 0.01f) << x << "," << y;
  }
  // The darkening is symmetric about both axes.
  EXPECT_EQ(got.at(3, 5, 0), got.at(124, 58, 0));
}

TEST(Vignette, ParameterSweepMatchesReference) {
  const ImageF input = aq::test::random_image(80, 48, 15, 0.0f, 2.0f);
  for (double radius : {0.0, 0.2, 0.45, 0.6}) {
    for (double strength : {0.3, 1.0}) {
      for (double softness : {0.0, 0.5, 1.0}) {
        const VignetteParams params{radius, strength, softness};
        const ImageF got = run(input, params);
        ASSERT_FALSE(got.empty());
        const ImageF expected = aq::reference::vignette(input, params);
        // A pixel right on the hard edge may flip; count mismatches instead of the max there.
        int mismatches = 0;
        for (size_t i = 0; i < got.pixels.size(); ++i) {
          if (std::abs(got.pixels[i] - expected.pixels[i]) > 2e-5) ++mismatches;
        }
        EXPECT_LE(mismatches, softness == 0.0 ? 8 : 0)
            << "radius " << radius << " strength " << strength << " softness " << softness;
      }
    }
  }
}

}  // namespace
