// Headless tests of the `noise` texture node against the CPU reference
// (reference/noise_texture_reference.h): every type in float and half precision, seamless
// tiling, resolution independence, seeds (same seed identical, other seed different), value
// ranges and Gaussian statistics, and a parameter sweep.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>

#include "aquarelle/reference/noise_reference.h"
#include "aquarelle/reference/noise_texture_reference.h"
#include "support/harness.h"

namespace {

using aq::ImageF;
using aq::reference::NoiseTextureParams;
using aq::reference::NoiseType;

constexpr NoiseType kAllTypes[] = {NoiseType::kPerlin, NoiseType::kFbm, NoiseType::kGaussian,
                                   NoiseType::kWorley};
const char* name_of(NoiseType t) {
  static const char* names[] = {"perlin", "fbm", "gaussian", "worley"};
  return names[int(t)];
}

ImageF run(const NoiseTextureParams& p, int width, int height, const char* precision = "float") {
  aq::test::RenderOptions options;
  options.precision = precision;
  const nlohmann::json params = {{"type", name_of(p.type)},
                                 {"scale", p.scale},
                                 {"octaves", p.octaves},
                                 {"seed", p.seed},
                                 {"range", p.unit_range ? "unit" : "raw"},
                                 {"width", width},
                                 {"height", height}};
  auto out = aq::test::run_node("noise", {}, params, options);
  EXPECT_TRUE(out.ok()) << (out.ok() ? "" : out.message());
  return out.ok() ? *out : ImageF();
}

NoiseTextureParams of_type(NoiseType type, int scale = 8) {
  NoiseTextureParams p;
  p.type = type;
  p.scale = scale;
  return p;
}

TEST(NoiseReference, Perlin3GradientIsTheDerivativeAndPeriodsHold) {
  // CPU only: the analytic gradient the caustics use for water normals against central
  // differences, and exact periodicity of the wrapped lattice (negative cells included).
  namespace n = aq::reference::noise;
  const n::Vec3 period{6.0, 5.0, 0.0};
  double worst = 0.0;
  for (int i = 0; i < 500; ++i) {
    const n::Vec3 p{-7.0 + 0.0371 * i, 3.3 - 0.0219 * i, 0.011 * i};
    const auto g = n::perlin3_with_gradient(p, period);
    const double h = 1e-6;
    const double dx =
        (n::perlin3({p.x + h, p.y, p.z}, period) - n::perlin3({p.x - h, p.y, p.z}, period)) /
        (2 * h);
    const double dy =
        (n::perlin3({p.x, p.y + h, p.z}, period) - n::perlin3({p.x, p.y - h, p.z}, period)) /
        (2 * h);
    const double dz =
        (n::perlin3({p.x, p.y, p.z + h}, period) - n::perlin3({p.x, p.y, p.z - h}, period)) /
        (2 * h);
    worst = std::max({worst, std::abs(dx - g.gradient.x), std::abs(dy - g.gradient.y),
                      std::abs(dz - g.gradient.z)});
    EXPECT_NEAR(g.value, n::perlin3({p.x + 6.0, p.y - 10.0, p.z}, period), 1e-12);
    EXPECT_LE(std::abs(g.value), 1.1);
  }
  EXPECT_LT(worst, 1e-6);
}

TEST(Noise, MatchesReferenceInFloat) {
  for (NoiseType type : kAllTypes) {
    for (auto [w, h] : {std::pair{64, 64}, std::pair{96, 40}}) {
      const NoiseTextureParams p = of_type(type);
      const ImageF expected = aq::reference::noise_texture(p, w, h);
      const ImageF got = run(p, w, h);
      ASSERT_EQ(got.width, w);
      ASSERT_EQ(got.height, h);
      const double err = aq::test::max_abs_diff(got, expected);
      EXPECT_LT(err, 2e-5) << name_of(type) << " " << w << "x" << h;
      EXPECT_GT(aq::test::psnr(got, expected), 90.0) << name_of(type);
      RecordProperty(std::string("max_abs_float_") + name_of(type), std::to_string(err));
    }
  }
}

TEST(Noise, MatchesReferenceInHalf) {
  for (NoiseType type : kAllTypes) {
    const NoiseTextureParams p = of_type(type);
    const ImageF expected = aq::reference::noise_texture(p, 64, 64);
    const ImageF got = run(p, 64, 64, "half");
    ASSERT_FALSE(got.empty());
    // Values in [0, 1]: within one RGBA16F step (2^-11 below 1; llvmpipe truncates).
    EXPECT_LT(aq::test::max_abs_diff(got, expected), 5e-4) << name_of(type);
  }
}

TEST(Noise, TilesSeamlesslyAcrossBothAxes) {
  // What lies one pixel past the right (top) edge of the continuous field is the first column
  // (row) of the texture, and the jump across the edge is no larger than inside the tile.
  const int n = 64;
  for (NoiseType type : kAllTypes) {
    const NoiseTextureParams p = of_type(type, 8);
    const ImageF tile = run(p, n, n);
    ASSERT_FALSE(tile.empty());
    double worst_wrap = 0.0, edge_jump = 0.0, inner_jump = 0.0;
    for (int i = 0; i < n; ++i) {
      const double beyond_right = aq::reference::noise_value(p, n + 0.5, i + 0.5, n, n);
      const double beyond_top = aq::reference::noise_value(p, i + 0.5, n + 0.5, n, n);
      const double before_left = aq::reference::noise_value(p, -0.5, i + 0.5, n, n);
      worst_wrap = std::max({worst_wrap, std::abs(beyond_right - tile.at(0, i, 0)),
                             std::abs(beyond_top - tile.at(i, 0, 0)),
                             std::abs(before_left - tile.at(n - 1, i, 0))});
      edge_jump += std::abs(tile.at(n - 1, i, 0) - tile.at(0, i, 0)) +
                   std::abs(tile.at(i, n - 1, 0) - tile.at(i, 0, 0));
      for (int j = 0; j + 1 < n; ++j) {
        inner_jump += (std::abs(tile.at(j + 1, i, 0) - tile.at(j, i, 0)) +
                       std::abs(tile.at(i, j + 1, 0) - tile.at(i, j, 0))) /
                      (n - 1);
      }
    }
    EXPECT_LT(worst_wrap, 2e-5) << name_of(type);
    // Gaussian noise is constant per cell and jumps at every cell border, the tile's edge
    // included: its seam is checked by the whole-cell test below.
    if (type != NoiseType::kGaussian) {
      EXPECT_LT(edge_jump, 2.0 * inner_jump) << name_of(type);
    }
  }
}

TEST(Noise, GaussianCellsAreWholeSoTheTileEndsOnACellBorder) {
  // 64 pixels, 8 cells: every 8 x 8 block is one constant value, and neighbouring blocks
  // (including the last and the first, across the edge) are independent samples.
  const ImageF tile = run(of_type(NoiseType::kGaussian, 8), 64, 64);
  ASSERT_FALSE(tile.empty());
  for (int y = 0; y < 64; ++y) {
    for (int x = 0; x < 64; ++x) {
      ASSERT_EQ(tile.at(x, y, 0), tile.at(x - x % 8, y - y % 8, 0)) << x << "," << y;
    }
  }
}

TEST(Noise, IsResolutionIndependent) {
  // Pixel centre x of a 64-pixel texture is pixel centre 3x + 1 of a 192-pixel one: both
  // sample the same continuous field there.
  for (NoiseType type : kAllTypes) {
    const ImageF small = run(of_type(type, 5), 64, 64);
    const ImageF large = run(of_type(type, 5), 192, 192);
    ASSERT_FALSE(small.empty() || large.empty());
    double worst = 0.0;
    for (int y = 0; y < 64; ++y) {
      for (int x = 0; x < 64; ++x) {
        worst = std::max(worst,
                         double(std::abs(small.at(x, y, 0) - large.at(3 * x + 1, 3 * y + 1, 0))));
      }
    }
    EXPECT_LT(worst, 1e-5) << name_of(type);
  }
}

TEST(Noise, SameSeedIsIdenticalOtherSeedDiffers) {
  for (NoiseType type : kAllTypes) {
    NoiseTextureParams p = of_type(type, 16);
    p.seed = 7;
    const ImageF a = run(p, 64, 64);
    const ImageF b = run(p, 64, 64);
    p.seed = 8;
    const ImageF c = run(p, 64, 64);
    EXPECT_EQ(aq::test::max_abs_diff(a, b), 0.0) << name_of(type);
    EXPECT_GT(aq::test::mean_abs_diff(a, c, 3), 0.03) << name_of(type);
  }
}

TEST(Noise, GaussianIsStandardNormalPerCell) {
  NoiseTextureParams p = of_type(NoiseType::kGaussian, 128);  // one cell per pixel
  p.unit_range = false;
  const ImageF got = run(p, 128, 128);
  ASSERT_FALSE(got.empty());
  double sum = 0.0, sum2 = 0.0;
  const double n = 128.0 * 128.0;
  for (int y = 0; y < 128; ++y) {
    for (int x = 0; x < 128; ++x) {
      sum += got.at(x, y, 0);
      sum2 += double(got.at(x, y, 0)) * got.at(x, y, 0);
    }
  }
  const double mean = sum / n;
  const double sd = std::sqrt(sum2 / n - mean * mean);
  // 16384 samples: the standard error of the mean is 0.008, of the deviation 0.006.
  EXPECT_NEAR(mean, 0.0, 0.03);
  EXPECT_NEAR(sd, 1.0, 0.03);
}

TEST(Noise, RawRangesHold) {
  for (NoiseType type : {NoiseType::kPerlin, NoiseType::kFbm, NoiseType::kWorley}) {
    NoiseTextureParams p = of_type(type, 13);
    p.unit_range = false;
    const ImageF got = run(p, 128, 128);
    ASSERT_FALSE(got.empty());
    float lo = 1e9f, hi = -1e9f;
    for (int y = 0; y < 128; ++y) {
      for (int x = 0; x < 128; ++x) {
        lo = std::min(lo, got.at(x, y, 0));
        hi = std::max(hi, got.at(x, y, 0));
      }
    }
    if (type == NoiseType::kWorley) {
      EXPECT_GE(lo, 0.0f);
      EXPECT_LT(hi, 1.4143f);
    } else {
      EXPECT_GE(lo, -1.0f - 1e-5f) << name_of(type);
      EXPECT_LE(hi, 1.0f + 1e-5f) << name_of(type);
      EXPECT_GT(hi - lo, 0.8f) << name_of(type);  // not a flat or tiny field
    }
  }
}

TEST(Noise, TinyAndThinSizesMatchTheReference) {
  for (auto [w, h] : {std::pair{1, 1}, std::pair{1, 37}, std::pair{200, 2}}) {
    for (NoiseType type : kAllTypes) {
      const NoiseTextureParams p = of_type(type, 3);
      const ImageF got = run(p, w, h);
      ASSERT_EQ(got.width, w);
      ASSERT_EQ(got.height, h);
      EXPECT_LT(aq::test::max_abs_diff(got, aq::reference::noise_texture(p, w, h)), 2e-5)
          << name_of(type) << " " << w << "x" << h;
    }
  }
}

TEST(Noise, ZeroSizeFollowsTheGraph) {
  aq::test::RenderOptions options;
  options.width = 40;
  options.height = 24;
  auto out = aq::test::run_node("noise", {}, {{"type", "perlin"}}, options);
  ASSERT_TRUE(out.ok()) << out.message();
  EXPECT_EQ(out->width, 40);
  EXPECT_EQ(out->height, 24);
}

TEST(Noise, ParameterSweepMatchesReferenceAndStaysInUnitRange) {
  for (NoiseType type : kAllTypes) {
    for (int scale : {1, 3, 16, 100}) {
      for (int octaves : {1, 4, 12}) {
        if (type != NoiseType::kFbm && octaves != 1) continue;
        NoiseTextureParams p = of_type(type, scale);
        p.octaves = octaves;
        p.seed = uint32_t(scale * 31 + octaves);
        const ImageF got = run(p, 48, 48);
        ASSERT_FALSE(got.empty());
        EXPECT_TRUE(aq::test::all_finite(got));
        EXPECT_LT(aq::test::max_abs_diff(got, aq::reference::noise_texture(p, 48, 48)), 5e-5)
            << name_of(type) << " scale " << scale << " octaves " << octaves;
        for (float v : got.pixels) {
          ASSERT_GE(v, -1e-5f);
          ASSERT_LE(v, 1.0f + 1e-5f);
        }
      }
    }
  }
}

}  // namespace
