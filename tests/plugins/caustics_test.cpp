// Headless tests of the `caustics` node, both estimators (`coverage`, the default, and Stam's
// `point`): flat water is exactly 1, energy (tile mean 1; by construction for coverage), no
// NaN/Inf and full coverage at extreme waves and on a surface with many folds, seamless
// tiling, determinism and animation, the same grid as the CPU references, and convergence to
// the exact box-filtered flux (reference/caustics_flux_reference.h) within the error the
// CPU predicts for the same grid.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "aquarelle/reference/caustics_flux_reference.h"
#include "aquarelle/reference/caustics_reference.h"
#include "support/harness.h"

namespace {

using aq::ImageF;
using aq::reference::CausticsParams;

constexpr const char* kCoverage = "coverage";
constexpr const char* kPoint = "point";
constexpr const char* kEstimators[] = {kCoverage, kPoint};

nlohmann::json to_json(const CausticsParams& p, bool normalize, const char* estimator = kCoverage) {
  return {{"estimator", estimator},
          {"resolution", p.resolution},
          {"grid", p.grid},
          {"depth", p.depth},
          {"amplitude", p.amplitude},
          {"wave_scale", p.wave_scale},
          {"speed", p.speed},
          {"eta", p.eta},
          {"max_intensity", p.max_intensity},
          {"normalize_energy", normalize}};
}

ImageF run(const CausticsParams& params, bool normalize, const char* precision = "float",
           int frame = 1, const char* estimator = kCoverage) {
  aq::test::RenderOptions options;
  options.precision = precision;
  options.frame = frame;
  auto out = aq::test::run_node("caustics", {}, to_json(params, normalize, estimator), options);
  EXPECT_TRUE(out.ok()) << (out.ok() ? "" : out.message());
  return out.ok() ? *out : ImageF();
}

ImageF run_point(const CausticsParams& params, bool normalize, const char* precision = "float",
                 int frame = 1) {
  return run(params, normalize, precision, frame, kPoint);
}

struct Stats {
  double mean = 0.0, min = 1e300, max = -1e300;
  bool finite = true;
};
Stats stats_of(const ImageF& image) {
  Stats s;
  for (int y = 0; y < image.height; ++y) {
    for (int x = 0; x < image.width; ++x) {
      const double v = image.at(x, y, 0);
      s.finite = s.finite && std::isfinite(v);
      s.mean += v;
      s.min = std::min(s.min, v);
      s.max = std::max(s.max, v);
    }
  }
  s.mean /= double(image.width) * image.height;
  return s;
}

double mean_abs_red(const ImageF& a, const ImageF& b) {
  return aq::test::mean_abs_diff(a, b, 1);
}

CausticsParams small(int resolution, int grid) {
  CausticsParams p;
  p.resolution = resolution;
  p.grid = grid;
  p.speed = 0.0;  // the pattern of t = 0 whatever time the harness gives the node
  return p;
}

TEST(Caustics, FlatWaterIsExactlyOneEverywhere) {
  for (const char* estimator : kEstimators) {
    for (const char* precision : {"float", "half"}) {
      for (bool normalize : {false, true}) {
        for (auto [resolution, grid] :
             {std::pair{64, 64}, std::pair{100, 37}, std::pair{32, 200}}) {
          CausticsParams p = small(resolution, grid);
          p.amplitude = 0.0;
          const ImageF got = run(p, normalize, precision, 1, estimator);
          ASSERT_EQ(got.width, resolution);
          for (int y = 0; y < got.height; ++y) {
            for (int x = 0; x < got.width; ++x) {
              for (int c = 0; c < 3; ++c) {
                ASSERT_EQ(got.at(x, y, c), 1.0f)
                    << estimator << " " << precision << " grid " << grid << " at " << x << "," << y;
              }
              ASSERT_EQ(got.at(x, y, 3), 1.0f);
            }
          }
        }
      }
    }
  }
}

TEST(Caustics, NoRefractionIsExactlyOneWhateverTheWaves) {
  CausticsParams p = small(64, 64);
  p.eta = 1.0;  // light goes straight through the surface
  p.amplitude = 0.1;
  for (const char* estimator : kEstimators) {
    const Stats s = stats_of(run(p, false, "float", 1, estimator));
    EXPECT_EQ(s.min, 1.0) << estimator;
    EXPECT_EQ(s.max, 1.0) << estimator;
  }
}

TEST(Caustics, CoverageConservesTheLightWithoutNormalisation) {
  // Every triangle gives out exactly the same whole number of counts whatever the waves, so the
  // tile's mean is 1 up to the float rounding of each texel, with no read-back and no rescaling,
  // even where folds, clamps and sub-texel triangles made the point estimator lose light.
  struct Case {
    double amplitude, depth, eta;
    int wave_scale, resolution, grid, frame;
  };
  for (const Case& c :
       {Case{0.02, 0.5, 1.0 / 1.333, 4, 64, 64, 1}, Case{0.02, 0.5, 1.0 / 1.333, 4, 100, 37, 9},
        Case{0.08, 2.0, 1.0 / 1.333, 4, 64, 128, 1}, Case{0.25, 4.0, 0.1, 2, 32, 16, 1},
        Case{0.1, 1.0, 0.5, 8, 48, 96, 5}}) {
    CausticsParams p = small(c.resolution, c.grid);
    p.amplitude = c.amplitude;
    p.depth = c.depth;
    p.eta = c.eta;
    p.wave_scale = c.wave_scale;
    p.speed = 0.5;
    const Stats s = stats_of(run(p, false, "float", c.frame));
    EXPECT_TRUE(s.finite);
    EXPECT_NEAR(s.mean, 1.0, 1e-6) << "amplitude " << c.amplitude << " depth " << c.depth << " eta "
                                   << c.eta << " grid " << c.grid;
    // Half precision rounds each texel to 11 significant bits, not the light's total.
    EXPECT_NEAR(stats_of(run(p, false, "half", c.frame)).mean, 1.0, 1e-3);
  }
}

TEST(Caustics, PointEnergyMeanIsOneWithinHalfAPercentWithoutNormalisation) {
  // The point estimator itself (no rescaling) nearly conserves the light at the default waves.
  for (int frame : {1, 7, 40}) {
    CausticsParams p = small(128, 128);
    p.speed = 0.5;
    const Stats s = stats_of(run_point(p, false, "float", frame));
    EXPECT_NEAR(s.mean, 1.0, 0.005) << "frame " << frame;
    RecordProperty("mean_frame_" + std::to_string(frame), std::to_string(s.mean));
  }
}

TEST(Caustics, PointEnergyMeanIsOneWithNormalisationWhateverTheWaves) {
  for (double amplitude : {0.005, 0.02, 0.08, 0.25}) {
    for (double depth : {0.1, 0.5, 2.0}) {
      CausticsParams p = small(64, 64);
      p.amplitude = amplitude;
      p.depth = depth;
      for (const char* precision : {"float", "half"}) {
        const Stats s = stats_of(run_point(p, true, precision));
        // Half precision rounds each pixel to 11 bits: the mean moves by far less than 0.5 %.
        EXPECT_NEAR(s.mean, 1.0, 0.005)
            << precision << " amplitude " << amplitude << " depth " << depth;
      }
    }
  }
}

TEST(Caustics, ExtremeWavesStayFiniteBoundedAndCoverEveryPixel) {
  struct Case {
    double amplitude, depth, eta;
    int grid;
  };
  for (const Case& c : {Case{0.25, 4.0, 1.0 / 1.333, 32}, Case{0.25, 4.0, 0.1, 8},
                        Case{0.25, 0.0, 1.0 / 1.333, 32}, Case{0.1, 1.0, 0.5, 16}}) {
    CausticsParams p = small(32, c.grid);
    p.amplitude = c.amplitude;
    p.depth = c.depth;
    p.eta = c.eta;
    for (const char* estimator : kEstimators) {
      for (bool normalize : {false, true}) {
        const ImageF got = run(p, normalize, "float", 1, estimator);
        ASSERT_FALSE(got.empty());
        EXPECT_TRUE(aq::test::all_finite(got));
        const Stats s = stats_of(got);
        // Every floor point has at least one preimage (the refraction map of the torus has
        // degree 1), so a pixel at 0 means a crack or an unrendered border.
        EXPECT_GT(s.min, 0.0) << estimator << " amplitude " << c.amplitude << " depth " << c.depth;
      }
    }
  }
}

TEST(Caustics, TilesWithoutASeam) {
  // The jump across the tile's edge (last column to first, last row to first) must look like
  // the jump between any two neighbouring columns or rows inside the tile.
  CausticsParams p = small(128, 128);
  p.amplitude = 0.01;  // smooth enough that neighbouring pixels are close
  for (const char* estimator : kEstimators) {
    const ImageF got = run(p, false, "float", 1, estimator);
    ASSERT_FALSE(got.empty());
    const int n = got.width;
    auto column_jump = [&](int x0, int x1) {
      double s = 0.0;
      for (int y = 0; y < n; ++y) s += std::abs(got.at(x1, y, 0) - got.at(x0, y, 0));
      return s / n;
    };
    auto row_jump = [&](int y0, int y1) {
      double s = 0.0;
      for (int x = 0; x < n; ++x) s += std::abs(got.at(x, y1, 0) - got.at(x, y0, 0));
      return s / n;
    };
    double inner_columns = 0.0, inner_rows = 0.0;
    for (int i = 0; i + 1 < n; ++i) {
      inner_columns += column_jump(i, i + 1) / (n - 1);
      inner_rows += row_jump(i, i + 1) / (n - 1);
    }
    EXPECT_LT(column_jump(n - 1, 0), 2.5 * inner_columns) << estimator;
    EXPECT_LT(row_jump(n - 1, 0), 2.5 * inner_rows) << estimator;
    RecordProperty(std::string("seam_column_over_inner_") + estimator,
                   std::to_string(column_jump(n - 1, 0) / inner_columns));
  }
}

TEST(Caustics, CoverageIsAsExactAtTheTileEdgesAsInside) {
  // The wrap is seamless when the texels along the tile's edges (where triangles refracted
  // across an edge land on the opposite side) match the CPU's exact coverage, which wraps
  // every texel index modulo the tile, as well as the texels inside do.
  CausticsParams p = small(64, 64);
  p.amplitude = 0.05;  // displacements of several texels
  const ImageF got = run(p, false);
  ASSERT_FALSE(got.empty());
  const ImageF expected = aq::reference::caustics_by_coverage(p, 64);
  double edge = 0.0, inside = 0.0;
  for (int y = 0; y < 64; ++y) {
    for (int x = 0; x < 64; ++x) {
      const double d = std::abs(got.at(x, y, 0) - expected.at(x, y, 0));
      const bool on_edge = x == 0 || y == 0 || x == 63 || y == 63;
      (on_edge ? edge : inside) = std::max(on_edge ? edge : inside, d);
    }
  }
  std::printf("caustics coverage vs CPU, max abs: tile edges %.2e, inside %.2e\n", edge, inside);
  EXPECT_LT(edge, 1e-3);
  EXPECT_LT(edge, 2.0 * inside + 1e-5);
}

TEST(Caustics, SameTimeIsDeterministicAndTimeAnimates) {
  CausticsParams p = small(64, 64);
  p.speed = 1.0;
  for (const char* estimator : kEstimators) {
    const ImageF a = run(p, true, "float", 1, estimator);
    const ImageF b = run(p, true, "float", 1, estimator);
    const ImageF later = run(p, true, "float", 13, estimator);
    EXPECT_EQ(aq::test::max_abs_diff(a, b), 0.0) << estimator;
    EXPECT_GT(mean_abs_red(a, later), 0.05) << estimator;
  }
}

TEST(Caustics, CoverageMatchesTheCpuOnTheSameGrid) {
  // The same box filter of the same piecewise-linear map, float and 31-bit counts on the GPU
  // against double on the CPU.
  for (auto [resolution, grid] : {std::pair{64, 32}, std::pair{64, 128}, std::pair{100, 37}}) {
    const CausticsParams p = small(resolution, grid);
    const ImageF expected = aq::reference::caustics_by_coverage(p, grid);
    const ImageF got = run(p, false);
    ASSERT_FALSE(got.empty());
    const double worst = aq::test::max_abs_diff(got, expected, 1);
    std::printf("caustics coverage GPU vs CPU, same grid %d at %d: max abs %.2e, L1 %.2e\n", grid,
                resolution, worst, mean_abs_red(got, expected));
    EXPECT_LT(worst, 2e-3) << "grid " << grid;
    EXPECT_LT(mean_abs_red(got, expected), 1e-4) << "grid " << grid;
  }
}

TEST(Caustics, CoverageWindowOfThreeKeepsTheLightOfTheWindowOfTwo) {
  // The closed form over 3 x 3 texels (the default) against 2 x 2 plus the texel-by-texel loop
  // for larger triangles: the same exact areas in real arithmetic, the same light in every
  // tile; in float they differ where a thin folded triangle's area is split between texels
  // (measured: 4 of 16384 texels by 2e-3 at grid 128, 3 of 9216 by 0.054 of a peak of 9 at
  // grid 64, steep waves), as the window of two differs from the CPU's double box filter
  // there (2e-3 and 0.02). Cells as large as texels and steep waves, as at final quality in
  // the flagship: many refracted triangles span three texels.
  for (auto [resolution, grid] : {std::pair{128, 128}, std::pair{96, 64}}) {
    CausticsParams p = small(resolution, grid);
    p.amplitude = 0.04;
    nlohmann::json narrow = to_json(p, false);
    narrow["window"] = 2;
    nlohmann::json wide = to_json(p, false);
    wide["window"] = 3;
    aq::test::RenderOptions options;
    options.precision = "float";
    auto two = aq::test::run_node("caustics", {}, narrow, options);
    auto three = aq::test::run_node("caustics", {}, wide, options);
    ASSERT_TRUE(two.ok()) << two.message();
    ASSERT_TRUE(three.ok()) << three.message();
    const ImageF expected = aq::reference::caustics_by_coverage(p, grid);
    const double between = aq::test::max_abs_diff(*two, *three, 1);
    const double between_mean = mean_abs_red(*two, *three);
    std::printf(
        "caustics coverage window 3 vs 2, grid %d at %d: max abs %.2e, L1 %.2e; vs CPU max "
        "%.2e, L1 %.2e (window 2: %.2e, %.2e)\n",
        grid, resolution, between, between_mean, aq::test::max_abs_diff(*three, expected, 1),
        mean_abs_red(*three, expected), aq::test::max_abs_diff(*two, expected, 1),
        mean_abs_red(*two, expected));
    EXPECT_GT(between, 0.0) << "the two windows must take different paths, or this proves nothing";
    EXPECT_LE(between, 0.1) << "grid " << grid;
    EXPECT_LE(between_mean, 2e-5) << "grid " << grid;
    EXPECT_LE(aq::test::max_abs_diff(*three, expected, 1), 0.1) << "grid " << grid;
    EXPECT_LE(mean_abs_red(*three, expected), 1e-4) << "grid " << grid;
    EXPECT_NEAR(stats_of(*three).mean, stats_of(*two).mean, 1e-6) << "the same light";
    EXPECT_NEAR(stats_of(*three).mean, 1.0, 1e-5) << "the light is conserved";
    EXPECT_GT(stats_of(*three).max, 2.0) << "the waves must focus, or nothing spans 3 texels";
  }
}

TEST(Caustics, PointMatchesTheCpuGridRefractionOnTheSameGrid) {
  // Same algorithm, same grid, float on the GPU against double on the CPU: only pixel centres
  // lying within rounding of a triangle edge may differ.
  for (int grid : {32, 64, 128}) {
    const CausticsParams p = small(64, grid);
    const ImageF expected = aq::reference::caustics_by_grid(p, grid);
    const ImageF got = run_point(p, false);
    ASSERT_FALSE(got.empty());
    const double l1 = mean_abs_red(got, expected);
    EXPECT_LT(l1, 0.01) << "grid " << grid;
    std::printf("caustics L1 GPU float vs CPU double, same grid %d: %.5f\n", grid, l1);
    RecordProperty("l1_same_grid_" + std::to_string(grid), std::to_string(l1));
  }
}

TEST(Caustics, WrapsDisplacementsOfMoreThanATileLikeTheReference) {
  // Rays travel up to ~1.5 tiles sideways: triangles land on copies two rings away. The CPU
  // reference wraps every covered pixel centre modulo the tile, independently of the node's
  // shifted copies.
  CausticsParams p = small(64, 32);
  p.depth = 3.0;
  p.amplitude = 0.08;
  p.eta = 0.5;
  const ImageF expected = aq::reference::caustics_by_grid(p, 32);
  const ImageF got = run_point(p, false);
  ASSERT_FALSE(got.empty());
  const double l1 = mean_abs_red(got, expected);
  std::printf("caustics L1 GPU vs CPU, same grid, displacements beyond a tile: %.5f\n", l1);
  EXPECT_LT(l1, 0.02 * stats_of(expected).mean);
  EXPECT_GT(stats_of(got).min, 0.0);
  // Coverage wraps each texel index modulo the tile: the same as the CPU's.
  const ImageF covered = run(p, false);
  ASSERT_FALSE(covered.empty());
  const ImageF exact = aq::reference::caustics_by_coverage(p, 32);
  EXPECT_LT(aq::test::max_abs_diff(covered, exact, 1), 2e-3);
  EXPECT_GT(stats_of(covered).min, 0.0);
}

TEST(Caustics, CoverageConvergesToTheBoxFilteredFluxWithinItsStatedError) {
  // The converged reference: the exact box-filtered flux on grids 128, 256, 512 in double; its
  // own error (Richardson, fitted order) must be far below what the node is checked to.
  const int resolution = 32;
  const CausticsParams base = small(resolution, 0);
  const auto converged = aq::reference::converge_caustic_flux(base, 512, 3);
  const ImageF reference = aq::reference::to_caustic_image(converged.texels, resolution);
  std::printf("caustics reference: order %.2f, RMS error %.2e, mean abs error %.2e\n",
              converged.order, converged.rms_error, converged.mean_abs_error);
  EXPECT_GT(converged.order, 1.5);
  EXPECT_LT(converged.rms_error, 2e-3);
  std::vector<double> errors;
  for (int grid : {16, 32, 64, 128}) {
    CausticsParams p = base;
    p.grid = grid;
    const ImageF got = run(p, false);
    ASSERT_FALSE(got.empty());
    // What the CPU says the same grid's error is: the node must be that, to float rounding
    // and the reference's own error.
    const double predicted = mean_abs_red(aq::reference::caustics_by_coverage(p, grid), reference);
    errors.push_back(mean_abs_red(got, reference));
    std::printf("caustics coverage L1 vs converged reference: grid %4d  %.5f (CPU %.5f)\n", grid,
                errors.back(), predicted);
    EXPECT_NEAR(errors.back(), predicted, converged.mean_abs_error + 2e-4) << "grid " << grid;
  }
  // Second order once the grid resolves the waves (from grid 32: 0.111, 0.040, 0.011): each
  // doubling divides the error by about 4, against 2 for point sampling.
  for (size_t i = 2; i < errors.size(); ++i) EXPECT_LT(errors[i], 0.4 * errors[i - 1]);
  EXPECT_LT(errors.back(), 0.015);
}

TEST(Caustics, PointConvergesToTheReferenceAsTheGridIsRefined) {
  // The converged reference: the same refraction on a 1024 x 1024 grid in double precision
  // (its own error, estimated against a 512 grid, is about 0.03 in L1 at this resolution).
  const int resolution = 64;
  const CausticsParams base = small(resolution, 0);
  const ImageF reference = aq::reference::caustics_by_grid(base, 1024);
  std::vector<double> errors;
  for (int grid : {16, 32, 64, 128, 256}) {
    CausticsParams p = base;
    p.grid = grid;
    const ImageF got = run_point(p, false);
    ASSERT_FALSE(got.empty());
    errors.push_back(mean_abs_red(got, reference));
    std::printf("caustics L1 error vs converged reference: grid %4d  %.4f\n", grid, errors.back());
    RecordProperty("l1_grid_" + std::to_string(grid), std::to_string(errors.back()));
  }
  for (size_t i = 1; i < errors.size(); ++i) EXPECT_LT(errors[i], errors[i - 1]);
  EXPECT_LT(errors[2], 0.25);  // grid = resolution, as the defaults
  EXPECT_LT(errors.back(), 0.08);
}

// Draft renders at a quarter of the size (render scale 1/4): the texture shrinks with it and
// the grid is an eighth of the one asked for.
TEST(Caustics, DraftQualityUsesAnEighthOfTheGridAndAQuarterOfTheTexture) {
  CausticsParams p = small(64, 128);
  aq::test::RenderOptions draft;
  draft.quality = "draft";
  draft.width = 100;  // not 64: an output at the working size would be resampled to the graph's
  draft.height = 60;
  auto got = aq::test::run_node("caustics", {}, to_json(p, false, kPoint), draft);
  ASSERT_TRUE(got.ok()) << got.message();
  ASSERT_EQ(got->width, 16);
  CausticsParams quarter = p;
  quarter.resolution = 16;
  EXPECT_LT(mean_abs_red(*got, aq::reference::caustics_by_grid(quarter, 16)), 0.01);
  EXPECT_GT(mean_abs_red(*got, aq::reference::caustics_by_grid(quarter, 128)), 0.05);
}

// Coverage's error is set by the grid against the waves more than by the texture: draft keeps
// half the grid and preview three quarters, while the texture shrinks with the render scale.
TEST(Caustics, CoverageDraftAndPreviewKeepMostOfTheGrid) {
  CausticsParams p = small(64, 128);
  for (auto [quality, scale, grid] : {std::tuple{"draft", 4, 64}, std::tuple{"preview", 2, 96}}) {
    aq::test::RenderOptions options;
    options.quality = quality;
    options.width = 100;  // not 64: an output at the working size would be resampled
    options.height = 60;
    auto got = aq::test::run_node("caustics", {}, to_json(p, false), options);
    ASSERT_TRUE(got.ok()) << got.message();
    ASSERT_EQ(got->width, 64 / scale) << quality;
    CausticsParams scaled = p;
    scaled.resolution = 64 / scale;
    EXPECT_LT(aq::test::max_abs_diff(*got, aq::reference::caustics_by_coverage(scaled, grid), 1),
              1e-4)
        << quality;
    EXPECT_GT(aq::test::max_abs_diff(*got, aq::reference::caustics_by_coverage(scaled, 128), 1),
              1e-3)
        << quality;
  }
}

TEST(Caustics, SmallestSizesWork) {
  for (const char* estimator : kEstimators) {
    for (auto [resolution, grid] : {std::pair{1, 4}, std::pair{2, 4}, std::pair{16, 4}}) {
      CausticsParams p = small(resolution, grid);
      const ImageF got = run(p, true, "float", 1, estimator);
      ASSERT_EQ(got.width, resolution);
      const Stats s = stats_of(got);
      EXPECT_TRUE(s.finite);
      EXPECT_GT(s.min, 0.0);
      EXPECT_NEAR(s.mean, 1.0, 1e-4) << estimator << " " << resolution;
    }
  }
}

TEST(Caustics, ReferenceAgreesWithIndependentPhotonSplatting) {
  // CPU only: the area-ratio reference (1024 grid, point samples at 256 px) averaged over
  // 32 x 32 pixel blocks against photon splatting (1024^2 stratified photons binned into the
  // same 8 x 8 blocks), which never computes an area: the two methods agree on the light's
  // distribution.
  CausticsParams p = small(256, 1024);
  const ImageF grid = aq::reference::caustics_by_grid(p, 1024);
  p.resolution = 8;
  const ImageF photons = aq::reference::caustics_by_photons(p, 1024);
  double l1 = 0.0;
  for (int by = 0; by < 8; ++by) {
    for (int bx = 0; bx < 8; ++bx) {
      double block = 0.0;
      for (int y = 0; y < 32; ++y) {
        for (int x = 0; x < 32; ++x) block += grid.at(bx * 32 + x, by * 32 + y, 0) / 1024.0;
      }
      l1 += std::abs(block - photons.at(bx, by, 0)) / 64.0;
    }
  }
  std::printf("caustics reference vs photon splatting, 8 x 8 blocks: L1 %.4f\n", l1);
  EXPECT_LT(l1, 0.02);
  EXPECT_NEAR(stats_of(photons).mean, 1.0, 1e-6);
  // The box-filtered flux straight at 8 x 8 texels (each block is a texel), on a grid of 256:
  // 32 cells per texel, converged far below this tolerance.
  const ImageF flux = aq::reference::caustics_by_coverage(p, 256);
  const double flux_l1 = mean_abs_red(flux, photons);
  std::printf("caustics box-filtered flux vs photon splatting, 8 x 8: L1 %.4f\n", flux_l1);
  EXPECT_LT(flux_l1, 0.01);
}

TEST(Caustics, HalfPrecisionMatchesFloat) {
  const CausticsParams p = small(64, 64);
  const ImageF f = run(p, false, "float");
  const ImageF h = run(p, false, "half");
  ASSERT_FALSE(f.empty());
  ASSERT_FALSE(h.empty());
  // Accumulation is in 32-bit float either way; the output rounds to 11 significant bits.
  double worst_relative = 0.0;
  for (int y = 0; y < f.height; ++y) {
    for (int x = 0; x < f.width; ++x) {
      worst_relative =
          std::max(worst_relative, double(std::abs(h.at(x, y, 0) - f.at(x, y, 0)) / f.at(x, y, 0)));
    }
  }
  EXPECT_LT(worst_relative, 1.0 / 1024.0);
}

TEST(Caustics, ParameterSweepStaysFiniteCoveredAndNearEnergy) {
  for (double depth : {0.05, 0.5, 1.5}) {
    for (double amplitude : {0.002, 0.02, 0.06}) {
      for (int wave_scale : {1, 2, 4}) {
        CausticsParams p = small(64, 64);
        p.depth = depth;
        p.amplitude = amplitude;
        p.wave_scale = wave_scale;
        for (const char* estimator : kEstimators) {
          const ImageF got = run(p, false, "float", 1, estimator);
          ASSERT_FALSE(got.empty());
          const Stats s = stats_of(got);
          EXPECT_TRUE(s.finite);
          EXPECT_GT(s.min, 0.0) << estimator << depth << " " << amplitude << " " << wave_scale;
          // Without normalisation, strong focusing loses some light to the point estimator's
          // clamp and sampling of sub-pixel triangles (the CPU reference gives 0.95 to 1.03
          // here); coverage loses none.
          EXPECT_NEAR(s.mean, 1.0, estimator == kPoint ? 0.06 : 1e-6)
              << estimator << " " << depth << " " << amplitude << " " << wave_scale;
        }
      }
    }
  }
}

TEST(Caustics, ManyFoldsStayFiniteAndKeepTheLight) {
  // Short steep waves over deep water: the refraction map folds over on itself all over the
  // tile (counted on the CPU: a large share of the triangles turn over), so nearly every texel
  // is lit through several layers and by caustic lines.
  CausticsParams p = small(64, 96);
  p.wave_scale = 8;
  p.amplitude = 0.06;
  p.depth = 2.0;
  int folded = 0;
  const int m = p.grid;
  auto position = [&](int i, int j) {
    const auto d = aq::reference::floor_displacement(double(i % m) / m, double(j % m) / m, p);
    return std::pair{double(i) / m + d.x, double(j) / m + d.y};
  };
  for (int j = 0; j < m; ++j) {
    for (int i = 0; i < m; ++i) {
      const auto [ax, ay] = position(i, j);
      const auto [bx, by] = position(i + 1, j);
      const auto [cx, cy] = position(i + 1, j + 1);
      folded += (bx - ax) * (cy - ay) - (by - ay) * (cx - ax) < 0.0;
    }
  }
  const double folded_share = double(folded) / (double(m) * m);
  std::printf("caustics many folds: %.0f %% of the triangles turned over\n", 100 * folded_share);
  ASSERT_GT(folded_share, 0.2);
  const ImageF got = run(p, false);
  ASSERT_FALSE(got.empty());
  EXPECT_TRUE(aq::test::all_finite(got));
  const Stats s = stats_of(got);
  EXPECT_GT(s.min, 0.0);
  EXPECT_NEAR(s.mean, 1.0, 1e-6);
  // The CPU's exact box filter of the same grid, folds and all.
  EXPECT_LT(aq::test::max_abs_diff(got, aq::reference::caustics_by_coverage(p, m), 1), 2e-3);
}

// With a scene connected, the texture gets about one texel per screen pixel where a tile looks
// largest: at the nearest receiver in view under the water. The plane_box scene seen straight
// down from 4 units up: the box top (y = 1) is 3 units away, the floor 4; a tile of 4 world
// units (the scene's caustic_tile) at depth z covers 4 H / (2 tan(fov / 2) z) pixels (pinhole
// camera), rounded up to 8.
ImageF footprint_caustics(const nlohmann::json& params, double water_height = 10.0,
                          double tile = 4.0) {
  nlohmann::json g = {
      {"aquarelle", 1},
      {"nodes",
       {{"scene",
         {{"type", "scene"},
          {"params",
           {{"preset", "plane_box"},
            {"camera_position", {0.0, 4.0, 0.0}},
            {"camera_target", {0.0, 0.0, -0.001}},
            {"fov", 50.0},
            {"water_height", water_height},
            {"caustic_tile", tile}}}}},
        {"caustics",
         {{"type", "caustics"}, {"params", params}, {"inputs", {{"scene", "scene.scene"}}}}}}},
      {"output", "caustics.image"}};
  aq::test::RenderOptions options;
  options.width = 96;
  options.height = 64;
  auto image = aq::test::render_graph(g.dump(), options);
  EXPECT_TRUE(image.ok()) << (image.ok() ? "" : image.message());
  return image.ok() ? *image : ImageF();
}

int footprint_width(double water_height, bool auto_resolution = true, double tile = 4.0) {
  const ImageF image =
      footprint_caustics({{"grid", 16}, {"resolution", 256}, {"auto_resolution", auto_resolution}},
                         water_height, tile);
  if (image.empty()) return -1;
  EXPECT_EQ(image.width, image.height);
  return image.width;
}

int pinhole_texels(double tile, int height, double fov_degrees, double depth) {
  const double pixels = tile * height / (2.0 * std::tan(fov_degrees * M_PI / 360.0) * depth);
  return static_cast<int>(std::ceil(pixels / 8.0) * 8.0);
}

TEST(Caustics, TextureSizeFollowsTheFootprintOfATileOnScreen) {
  EXPECT_EQ(footprint_width(10.0), pinhole_texels(4.0, 64, 50.0, 3.0));  // box top nearest
  // Water at 0.5: the box top is dry, the nearest receiver under water is 3.5 away.
  EXPECT_EQ(footprint_width(0.5), pinhole_texels(4.0, 64, 50.0, 3.5));
  EXPECT_EQ(footprint_width(-5.0), 16);  // nothing under the water in view
  EXPECT_EQ(footprint_width(10.0, false), 256);
  // The tile's size is the scene's (the period cel_light projects with by default).
  EXPECT_EQ(footprint_width(10.0, true, 2.0), pinhole_texels(2.0, 64, 50.0, 3.0));
}

// At final quality with the footprint's texture and auto_grid, the grid is no finer than a cell
// per two texels of it (the proxy presets' density): the same image as that grid by hand.
TEST(Caustics, FinalGridFollowsTheFootprintTexture) {
  const int width = footprint_width(10.0);
  ASSERT_GT(width, 8);
  const ImageF automatic = footprint_caustics(
      {{"grid", 256}, {"resolution", 256}, {"auto_resolution", true}, {"auto_grid", true}});
  const ImageF by_hand = footprint_caustics(
      {{"grid", (width + 1) / 2}, {"resolution", width}, {"auto_resolution", false}});
  const ImageF fine =
      footprint_caustics({{"grid", 256}, {"resolution", width}, {"auto_resolution", false}});
  ASSERT_FALSE(automatic.empty());
  ASSERT_FALSE(by_hand.empty());
  ASSERT_FALSE(fine.empty());
  EXPECT_EQ(aq::test::max_abs_diff(automatic, by_hand), 0.0);
  EXPECT_GT(aq::test::max_abs_diff(automatic, fine), 1e-3) << "the grid asked for is not used";
  // auto_grid off (the default): the footprint still sizes the texture, the grid is the one
  // asked for.
  const ImageF asked =
      footprint_caustics({{"grid", 256}, {"resolution", 256}, {"auto_resolution", true}});
  ASSERT_FALSE(asked.empty());
  EXPECT_EQ(aq::test::max_abs_diff(asked, fine), 0.0);
}

}  // namespace
