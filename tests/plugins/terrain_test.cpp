// `object` source `terrain` (issue 38, seed 001's sea floor): every visible floor point the
// g-buffer reports lies on the piecewise-linear grid of the README's height formula (two Perlin
// frequencies plus the cliff), computed here from the maths with the plugin's seeded Perlin
// noise (the primitive, not the code under test); the cliff rises at the back edge; a
// non-finite terrain parameter (the command line's `--set` can give one) is an error naming it.
#include <gtest/gtest.h>

#include <aquarelle/core/evaluator.h>
#include <aquarelle/core/gl_context.h>

#include <nlohmann/json.hpp>

#include <limits>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>

#include "../../plugins/scene/perlin.h"
#include "app/cli_support.h"
#include "support/harness.h"

namespace {

using aq::ImageF;

struct Terrain {
  double swell = 0.08, swell_frequency = 3.0, bumps = 0.012, bumps_frequency = 24.0, cliff = 0.0;
  uint64_t seed = 7;
  int cells = 128;
};

double smoothstep(double lo, double hi, double x) {
  const double t = std::clamp((x - lo) / (hi - lo), 0.0, 1.0);
  return t * t * (3.0 - 2.0 * t);
}

// README: h = swell·P1(fs x, fs z) + bumps·P2(fb x, fb z) + cliff·c, c = smoothstep(0.28, 0.38,
// w)·smoothstep(0.3, 0.1, x), w = -z + 0.05·P2(5x + 11.5, 0.5); P1 seeded with `seed`, P2 with
// seed ^ 0x9e3779b97f4a7c15.
double height(const Terrain& t, double x, double z) {
  const scene::Perlin2 p1(t.seed), p2(t.seed ^ 0x9e3779b97f4a7c15ull);
  const double w = -z + 0.05 * p2(5.0 * x + 11.5, 0.5);
  return t.swell * p1(t.swell_frequency * x, t.swell_frequency * z) +
         t.bumps * p2(t.bumps_frequency * x, t.bumps_frequency * z) +
         (t.cliff == 0.0 ? 0.0 : t.cliff * smoothstep(0.28, 0.38, w) * smoothstep(0.3, 0.1, x));
}

// The grid's linear interpolant at (x, z): vertices at x = -0.5 + i/n, z = 0.5 - j/n, each cell
// split along its (i, j)-(i+1, j+1) diagonal.
double grid_height(const Terrain& t, double x, double z) {
  const int n = t.cells;
  const double u = (x + 0.5) * n, v = (0.5 - z) * n;
  const int i = std::clamp(static_cast<int>(std::floor(u)), 0, n - 1);
  const int j = std::clamp(static_cast<int>(std::floor(v)), 0, n - 1);
  const double fu = u - i, fv = v - j;
  auto h = [&](int a, int b) { return height(t, -0.5 + double(a) / n, 0.5 - double(b) / n); };
  // Triangle (i,j),(i+1,j),(i+1,j+1) when fu >= fv, else (i,j),(i+1,j+1),(i,j+1).
  if (fu >= fv)
    return h(i, j) + fu * (h(i + 1, j) - h(i, j)) + fv * (h(i + 1, j + 1) - h(i + 1, j));
  return h(i, j) + fv * (h(i, j + 1) - h(i, j)) + fu * (h(i + 1, j + 1) - h(i, j + 1));
}

nlohmann::json graph(const Terrain& t) {
  return {{"aquarelle", 1},
          {"nodes",
           {{"floor",
             {{"type", "object"},
              {"params",
               {{"source", "terrain"},
                {"seed", t.seed},
                {"terrain_swell", t.swell},
                {"terrain_swell_frequency", t.swell_frequency},
                {"terrain_bumps", t.bumps},
                {"terrain_bumps_frequency", t.bumps_frequency},
                {"terrain_cliff", t.cliff}}}}},
            {"join",
             {{"type", "scene_join"},
              {"params",
               {{"camera_position", {0.0, 1.6, 0.9}},
                {"camera_target", {0.0, 0.0, 0.0}},
                {"fov", 50.0},
                {"environment", "none"}}},
              {"inputs", {{"objects", {"floor.object"}}}}}},
            {"gbuf", {{"type", "gbuffer"}, {"inputs", {{"scene", "join.scene"}}}}}}},
          {"output", "gbuf.position"}};
}

ImageF positions(const Terrain& t) {
  aq::test::RenderOptions options;
  options.width = options.height = 96;
  options.output = "gbuf.position";
  auto image = aq::test::render_graph(graph(t).dump(), options);
  EXPECT_TRUE(image.ok()) << (image.ok() ? "" : image.message());
  return image.ok() ? *image : ImageF();
}

// Largest |y - grid height| over the floor's pixels, and how many there are.
std::pair<double, int> off_the_grid(const Terrain& t, const ImageF& p) {
  double largest = 0.0;
  int covered = 0;
  for (int y = 0; y < p.height; ++y) {
    for (int x = 0; x < p.width; ++x) {
      if (p.at(x, y, 3) != 1.0f) continue;
      ++covered;
      largest =
          std::max(largest, std::abs(p.at(x, y, 1) - grid_height(t, p.at(x, y, 0), p.at(x, y, 2))));
    }
  }
  return {largest, covered};
}

TEST(Terrain, SwellsAndBumpsFollowTheSeedsTwoFrequencies) {
  Terrain t;
  const ImageF p = positions(t);
  const auto [error, covered] = off_the_grid(t, p);
  EXPECT_GT(covered, 96 * 96 / 4);
  EXPECT_LT(error, 2e-4) << "positions are float; the swells are 0.08 high";
  // Not flat: the heights span most of the swell.
  double lo = 1e9, hi = -1e9;
  for (int i = 0; i < p.width * p.height; ++i) {
    if (p.pixels[4 * i + 3] != 1.0f) continue;
    lo = std::min<double>(lo, p.pixels[4 * i + 1]), hi = std::max<double>(hi, p.pixels[4 * i + 1]);
  }
  EXPECT_GT(hi - lo, 0.05);
}

TEST(Terrain, TheCliffRisesAtTheBackEdge) {
  Terrain t;
  t.cliff = 0.3;
  const ImageF p = positions(t);
  const auto [error, covered] = off_the_grid(t, p);
  EXPECT_GT(covered, 96 * 96 / 4);
  EXPECT_LT(error, 5e-4) << "the cliff's face is steep: float positions on a 0.3 wall";
  double back = -1e9;
  for (int i = 0; i < p.width * p.height; ++i) {
    if (p.pixels[4 * i + 3] == 1.0f && p.pixels[4 * i + 2] < -0.45f && p.pixels[4 * i] < 0.0f) {
      back = std::max<double>(back, p.pixels[4 * i + 1]);
    }
  }
  EXPECT_GT(back, 0.2) << "the back edge is up the cliff on the left";
}

TEST(Terrain, ANonFiniteParameterIsAnErrorNamingIt) {
  const auto dir = aq::test::scratch_dir("terrain_nan");
  std::ofstream(dir / "g.json") << graph(Terrain{}).dump(2);
  const auto result =
      aq::test::aquarelle("render " + (dir / "g.json").string() + " -o " +
                          (dir / "out.exr").string() + " --set floor.terrain_swell=nan");
  EXPECT_NE(result.exit_code, 0) << result.output;
  EXPECT_NE(result.output.find("terrain_swell"), std::string::npos) << result.output;
}

// The graph reader refuses a NaN before any node sees it; a parameter set in memory (the
// editor, the Python module, a host of our library) reaches the node itself, which must refuse
// it by name rather than build a mesh of NaNs.
TEST(Terrain, ANonFiniteParameterReachingTheNodeIsRefusedByTheNode) {
  auto context = aq::create_headless_context(aq::GlBackend::kAuto);
  ASSERT_TRUE(context.ok()) << context.message();
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  for (const char* name : {"terrain_swell", "terrain_swell_frequency", "terrain_bumps",
                           "terrain_bumps_frequency", "terrain_cliff"}) {
    for (double bad : {nan, inf}) {
      aq::Evaluator evaluator(**context, aq::test::registry());
      auto image =
          aq::test::evaluate_text(evaluator, graph(Terrain{}).dump(), 1,
                                  [&](aq::Graph& g) { g.nodes["floor"].params[name] = bad; });
      ASSERT_FALSE(image.ok()) << name << " = " << bad << " rendered";
      EXPECT_NE(image.message().find(name), std::string::npos) << image.message();
      EXPECT_NE(image.message().find("floor"), std::string::npos) << image.message();
    }
  }
  // The same evaluator renders again once the parameter is a number.
  aq::Evaluator evaluator(**context, aq::test::registry());
  auto image = aq::test::evaluate_text(evaluator, graph(Terrain{}).dump(), 1);
  EXPECT_TRUE(image.ok()) << image.message();
}

// `terrain_cells` sets the grid: the floor's positions lie on the grid of that many cells
// (checked against the README formula's interpolant at 32 cells, far from the 128 default).
TEST(Terrain, TheGridHasTerrainCellsCells) {
  Terrain t;
  t.cells = 32;
  nlohmann::json g = graph(t);
  g["nodes"]["floor"]["params"]["terrain_cells"] = 32;
  aq::test::RenderOptions options;
  options.width = options.height = 96;
  options.output = "gbuf.position";
  auto p = aq::test::render_graph(g.dump(), options);
  ASSERT_TRUE(p.ok()) << p.message();
  const auto [error, covered] = off_the_grid(t, *p);
  EXPECT_GT(covered, 96 * 96 / 4);
  EXPECT_LT(error, 2e-4);
  Terrain fine = t;
  fine.cells = 128;
  EXPECT_GT(off_the_grid(fine, *p).first, 1e-3) << "a 32-cell grid is not the 128 one";
}

}  // namespace
