// Headless tests of the `pigment_mix` node against the CPU double reference
// (reference/pigment_mix.h): each mode against its definition on random colours, blue and
// yellow make green with Kubelka–Munk (and not with rgb or cmyk), a colour mixed with itself is
// itself, factors 0 and 1, mixing with white and black, NaN and Inf inputs stay finite.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "aquarelle/reference/pigment_mix.h"
#include "support/harness.h"

namespace {

using aq::ImageF;
using aq::reference::MixMode;
using aq::reference::Rgb;

const char* mode_name(MixMode mode) {
  return mode == MixMode::kRgb ? "rgb" : mode == MixMode::kCmyk ? "cmyk" : "kubelka_munk";
}

ImageF run(const ImageF& a, const ImageF& b, MixMode mode, double factor) {
  auto out = aq::test::run_node("pigment_mix", {{"a", a}, {"b", b}},
                                {{"mode", mode_name(mode)}, {"factor", factor}});
  EXPECT_TRUE(out.ok()) << (out.ok() ? "" : out.message());
  return out.ok() ? *out : ImageF();
}

Rgb at(const ImageF& image, int x, int y) {
  return {image.at(x, y, 0), image.at(x, y, 1), image.at(x, y, 2)};
}

constexpr MixMode kModes[] = {MixMode::kRgb, MixMode::kCmyk, MixMode::kKubelkaMunk};

TEST(PigmentMix, EveryModeMatchesItsReferenceOnRandomColours) {
  const ImageF a = aq::test::random_image(32, 32, 1);
  const ImageF b = aq::test::random_image(32, 32, 2);
  for (MixMode mode : kModes) {
    for (double factor : {0.0, 0.3, 0.5, 1.0}) {
      const ImageF gpu = run(a, b, mode, factor);
      const ImageF cpu = aq::reference::pigment_mix(a, b, factor, mode);
      // Kubelka–Munk goes through sinh, cosh and arccoth in single precision.
      const double bound = mode == MixMode::kKubelkaMunk ? 2e-3 : 1e-5;
      EXPECT_LT(aq::test::max_abs_diff(gpu, cpu, 3), bound)
          << mode_name(mode) << " factor " << factor;
    }
  }
}

TEST(PigmentMix, BlueAndYellowMakeGreenOnlyAsPigments) {
  const ImageF blue = aq::test::constant_image(4, 4, 0.1f, 0.2f, 0.8f);
  const ImageF yellow = aq::test::constant_image(4, 4, 0.9f, 0.8f, 0.1f);
  const Rgb km = at(run(blue, yellow, MixMode::kKubelkaMunk, 0.5), 1, 1);
  EXPECT_GT(km[1], km[0] + 0.07) << "green over red";
  EXPECT_GT(km[1], km[2] + 0.07) << "green over blue";
  const Rgb rgb = at(run(blue, yellow, MixMode::kRgb, 0.5), 1, 1);
  EXPECT_LT(std::abs(rgb[1] - rgb[0]), 0.05) << "light mixes to grey";
  const Rgb cmyk = at(run(blue, yellow, MixMode::kCmyk, 0.5), 1, 1);
  EXPECT_LT(cmyk[1] - std::min(cmyk[0], cmyk[2]), 0.1) << "the seed's CMYK lerp stays greyish";
}

TEST(PigmentMix, AColourMixedWithItselfIsItself) {
  const ImageF a = aq::test::random_image(16, 16, 3, 0.02f, 0.98f);
  for (MixMode mode : kModes) {
    const ImageF gpu = run(a, a, mode, 0.5);
    EXPECT_LT(aq::test::max_abs_diff(gpu, a, 3), mode == MixMode::kKubelkaMunk ? 2e-3 : 1e-5)
        << mode_name(mode);
  }
}

TEST(PigmentMix, FactorZeroKeepsAAndOneGivesB) {
  const ImageF a = aq::test::random_image(16, 16, 4, 0.02f, 0.98f);
  const ImageF b = aq::test::random_image(16, 16, 5, 0.02f, 0.98f);
  for (MixMode mode : kModes) {
    const double bound = mode == MixMode::kKubelkaMunk ? 2e-3 : 1e-5;
    EXPECT_LT(aq::test::max_abs_diff(run(a, b, mode, 0.0), a, 3), bound) << mode_name(mode);
    EXPECT_LT(aq::test::max_abs_diff(run(a, b, mode, 1.0), b, 3), bound) << mode_name(mode);
  }
}

TEST(PigmentMix, WhiteLightensAndBlackDarkensWithoutLeavingTheRange) {
  const ImageF a = aq::test::random_image(16, 16, 6, 0.1f, 0.9f);
  const ImageF white = aq::test::constant_image(16, 16, 1.0f, 1.0f, 1.0f);
  const ImageF black = aq::test::constant_image(16, 16, 0.0f, 0.0f, 0.0f);
  for (MixMode mode : kModes) {
    const ImageF lighter = run(a, white, mode, 0.5);
    const ImageF darker = run(a, black, mode, 0.5);
    for (int y = 0; y < 16; ++y)
      for (int x = 0; x < 16; ++x)
        for (int c = 0; c < 3; ++c) {
          EXPECT_GE(lighter.at(x, y, c), a.at(x, y, c) - 1e-4) << mode_name(mode);
          EXPECT_LE(lighter.at(x, y, c), 1.0f) << mode_name(mode);
          EXPECT_GE(darker.at(x, y, c), 0.0f) << mode_name(mode);
          // CMYK interpolation is not monotone per channel (black has no c, m, y): only its
          // value (the largest channel) must not grow.
          if (mode != MixMode::kCmyk) {
            EXPECT_LE(darker.at(x, y, c), a.at(x, y, c) + 1e-4) << mode_name(mode);
          }
        }
    if (mode == MixMode::kCmyk) {
      for (int y = 0; y < 16; ++y)
        for (int x = 0; x < 16; ++x) {
          auto value = [&](const ImageF& im) {
            return std::max({im.at(x, y, 0), im.at(x, y, 1), im.at(x, y, 2)});
          };
          EXPECT_LE(value(darker), value(a) + 1e-5);
        }
    }
  }
}

TEST(PigmentMix, TinySizesAndBothBackends) {
  for (const char* gl : {"egl", "osmesa"}) {
    for (auto [w, h] : {std::pair{1, 1}, {1, 9}, {9, 1}, {13, 7}}) {
      const ImageF a = aq::test::random_image(w, h, 7), b = aq::test::random_image(w, h, 8);
      aq::test::RenderOptions options;
      options.width = w;
      options.height = h;
      options.gl = gl;
      auto out = aq::test::run_node("pigment_mix", {{"a", a}, {"b", b}}, {}, options);
      ASSERT_TRUE(out.ok()) << out.message();
      EXPECT_LT(aq::test::max_abs_diff(
                    *out, aq::reference::pigment_mix(a, b, 0.5, MixMode::kKubelkaMunk), 3),
                2e-3)
          << gl << " " << w << "x" << h;
    }
  }
}

TEST(PigmentMix, NanAndInfinityStayFinite) {
  const float nan = std::numeric_limits<float>::quiet_NaN();
  const float inf = std::numeric_limits<float>::infinity();
  ImageF a = aq::test::constant_image(4, 4, nan, inf, -inf, nan);
  ImageF b = aq::test::constant_image(4, 4, 0.5f, nan, inf, nan);
  for (MixMode mode : kModes) {
    EXPECT_TRUE(aq::test::all_finite(run(a, b, mode, 0.5))) << mode_name(mode);
    EXPECT_TRUE(aq::test::all_finite(run(b, a, mode, 0.5))) << mode_name(mode);
  }
}

}  // namespace
