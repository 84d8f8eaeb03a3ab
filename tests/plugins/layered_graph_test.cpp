// graphs/layered.json (the underwater scene painted layer by layer) and graphs/three_cubes.json
// (seed 003's three cubes, wet-to-dry and wet-in-wet side by side) end to end at a small size:
// both validate, render finite images that are paintings (objects on paper, not flat), and in
// the cubes the lit fronts are lighter than the shaded sides and the wet-in-wet cube's colour
// feathers into the paper where the wet-to-dry cubes stop.
#include <gtest/gtest.h>

#include <aquarelle/core/evaluator.h>
#include <aquarelle/core/graph_io.h>

#include <cmath>
#include <fstream>
#include <sstream>

#include "support/harness.h"

namespace {

aq::test::RenderOptions small() {
  aq::test::RenderOptions options;
  options.width = 160;
  options.height = 90;
  options.precision = "half";
  return options;
}

double luminance(const aq::ImageF& im, int x, int y) {
  return 0.2126 * im.at(x, y, 0) + 0.7152 * im.at(x, y, 1) + 0.0722 * im.at(x, y, 2);
}

double stddev_luminance(const aq::ImageF& im) {
  double sum = 0.0, sum2 = 0.0;
  for (int y = 0; y < im.height; ++y)
    for (int x = 0; x < im.width; ++x) {
      const double l = luminance(im, x, y);
      sum += l;
      sum2 += l * l;
    }
  const double n = static_cast<double>(im.width) * im.height;
  return std::sqrt(std::max(0.0, sum2 / n - (sum / n) * (sum / n)));
}

TEST(LayeredGraphs, BothValidate) {
  for (const char* graph :
       {"graphs/layered.json", "graphs/three_cubes.json", "graphs/three_cubes_cmyk.json"}) {
    const aq::ReadResult result =
        aq::read_graph_file(aq::test::source_path(graph), aq::test::registry());
    EXPECT_TRUE(result.problems.empty())
        << graph << ": " << (result.problems.empty() ? "" : aq::format_problem(result.problems[0]));
  }
}

TEST(LayeredGraphs, UnderwaterRendersAsAPainting) {
  auto out = aq::test::render_graph_file(aq::test::source_path("graphs/layered.json"), small());
  ASSERT_TRUE(out.ok()) << out.message();
  EXPECT_TRUE(aq::test::all_finite(*out));
  EXPECT_GT(stddev_luminance(*out), 0.05) << "objects on paper, not a flat image";
  // The top rows are open water: paper.
  EXPECT_GT(luminance(*out, 80, 88), 0.85);
}

TEST(LayeredGraphs, ThreeCubesLighterFrontsAndSideBySideEdges) {
  auto options = small();
  auto out = aq::test::render_graph_file(aq::test::source_path("graphs/three_cubes.json"), options);
  ASSERT_TRUE(out.ok()) << out.message();
  EXPECT_TRUE(aq::test::all_finite(*out));
  options.output = "gbuf.id";
  auto ids = aq::test::render_graph_file(aq::test::source_path("graphs/three_cubes.json"), options);
  ASSERT_TRUE(ids.ok()) << ids.message();
  options.output = "gbuf.normal";
  auto normals =
      aq::test::render_graph_file(aq::test::source_path("graphs/three_cubes.json"), options);
  ASSERT_TRUE(normals.ok()) << normals.message();
  // Per cube: mean luminance of its front (+z) face and of its other visible faces (top, side).
  for (int cube = 1; cube <= 3; ++cube) {
    double front = 0.0, side = 0.0;
    int front_n = 0, side_n = 0;
    for (int y = 0; y < 90; ++y)
      for (int x = 0; x < 160; ++x) {
        if (ids->at(x, y, 0) != static_cast<float>(cube)) continue;
        if (normals->at(x, y, 2) > 0.9f) front += luminance(*out, x, y), ++front_n;
        if (std::abs(normals->at(x, y, 2)) < 0.1f) side += luminance(*out, x, y), ++side_n;
      }
    ASSERT_GT(front_n, 20) << "cube " << cube;
    ASSERT_GT(side_n, 5) << "cube " << cube;
    EXPECT_GT(front / front_n, side / side_n + 0.02) << "cube " << cube;
  }
  // Wet-in-wet (the green cube, id 3) spreads colour into the paper around it; the wet-to-dry
  // cubes leave the paper a few pixels off their silhouette.
  auto painted_ring = [&](int cube) {
    int painted = 0, ring = 0;
    for (int y = 3; y < 87; ++y)
      for (int x = 3; x < 157; ++x) {
        if (ids->at(x, y, 0) != 0.0f) continue;
        bool near = false;
        for (int dy = -3; dy <= 3 && !near; ++dy)
          for (int dx = -3; dx <= 3 && !near; ++dx)
            near = ids->at(x + dx, y + dy, 0) == static_cast<float>(cube);
        if (!near) continue;
        ++ring;
        painted += luminance(*out, x, y) < 0.85 ? 1 : 0;
      }
    return ring > 0 ? static_cast<double>(painted) / ring : 0.0;
  };
  EXPECT_GT(painted_ring(3), painted_ring(1) + 0.2);
  EXPECT_GT(painted_ring(3), painted_ring(2) + 0.2);
}

TEST(LayeredGraphs, ThreeCubesTopsDifferFromFronts) {
  // Faces that face the light differently are painted differently: per cube, the mean colour
  // of its top (+y) and of its front (+z) face differ clearly (seed 003's cubes).
  auto options = small();
  const std::string graph = aq::test::source_path("graphs/three_cubes.json");
  auto out = aq::test::render_graph_file(graph, options);
  ASSERT_TRUE(out.ok()) << out.message();
  options.output = "gbuf.id";
  auto ids = aq::test::render_graph_file(graph, options);
  ASSERT_TRUE(ids.ok()) << ids.message();
  options.output = "gbuf.normal";
  auto normals = aq::test::render_graph_file(graph, options);
  ASSERT_TRUE(normals.ok()) << normals.message();
  for (int cube = 1; cube <= 3; ++cube) {
    double top[3] = {}, front[3] = {};
    int top_n = 0, front_n = 0;
    for (int y = 0; y < 90; ++y)
      for (int x = 0; x < 160; ++x) {
        if (ids->at(x, y, 0) != static_cast<float>(cube)) continue;
        const bool is_top = normals->at(x, y, 1) > 0.9f, is_front = normals->at(x, y, 2) > 0.9f;
        for (int c = 0; c < 3; ++c) {
          if (is_top) top[c] += out->at(x, y, c);
          if (is_front) front[c] += out->at(x, y, c);
        }
        top_n += is_top ? 1 : 0;
        front_n += is_front ? 1 : 0;
      }
    ASSERT_GT(top_n, 10) << "cube " << cube;
    ASSERT_GT(front_n, 10) << "cube " << cube;
    double largest = 0.0;
    for (int c = 0; c < 3; ++c)
      largest = std::max(largest, std::abs(top[c] / top_n - front[c] / front_n));
    EXPECT_GT(largest, 0.12) << "cube " << cube << ": top and front look alike";
  }
}

TEST(LayeredGraphs, ShippedGraphsMixWithCmykAndKubelkaMunk) {
  // Seed 004's two subtractive mixings each have a shipped graph, and they paint differently
  // (the colour chart in docs/layered.md shows why: a CMYK lerp of two pigments stays near
  // grey where Kubelka-Munk darkens and saturates).
  const aq::ReadResult km =
      aq::read_graph_file(aq::test::source_path("graphs/three_cubes.json"), aq::test::registry());
  const aq::ReadResult cmyk = aq::read_graph_file(
      aq::test::source_path("graphs/three_cubes_cmyk.json"), aq::test::registry());
  ASSERT_TRUE(km.ok() && cmyk.ok());
  EXPECT_EQ(km.graph.nodes.at("layered").params.at("mixing"), "kubelka_munk");
  EXPECT_EQ(cmyk.graph.nodes.at("layered").params.at("mixing"), "cmyk");
  auto a = aq::test::render_graph_file(aq::test::source_path("graphs/three_cubes.json"), small());
  auto b =
      aq::test::render_graph_file(aq::test::source_path("graphs/three_cubes_cmyk.json"), small());
  ASSERT_TRUE(a.ok() && b.ok());
  EXPECT_GT(aq::test::max_abs_diff(*a, *b, 3), 0.1);
}

// The fast method keeps (threshold, paper height) per pixel between calls and trusts the
// paper's damage: a node instance that painted with one paper and then gets another must paint
// what a fresh instance paints with the new paper, bit for bit.
TEST(LayeredGraphs, FastMethodFollowsAPaperChange) {
  auto context = aq::create_headless_context(aq::GlBackend::kAuto);
  ASSERT_TRUE(context.ok()) << context.message();
  std::ifstream file(aq::test::source_path("graphs/three_cubes.json"));
  std::stringstream text;
  text << file.rdbuf();
  aq::Evaluator kept(**context, aq::test::registry());
  aq::Evaluator fresh(**context, aq::test::registry());
  auto render = [&](aq::Evaluator& evaluator, double roughness) {
    auto pixels = aq::test::evaluate_text(evaluator, text.str(), 1, [&](aq::Graph& graph) {
      graph.settings.width = 128;
      graph.settings.height = 72;
      graph.settings.quality = "final";
      graph.nodes["paper"].params["roughness"] = roughness;
      graph.nodes["paper"].params["grain_scale"] = 20.0;
      graph.nodes["layered"].params["method"] = "fast";
    });
    EXPECT_TRUE(pixels.ok()) << pixels.message();
    return pixels.ok() ? *pixels : aq::ImageF();
  };
  const aq::ImageF before = render(kept, 0.1);
  const aq::ImageF after = render(kept, 1.0);
  const aq::ImageF expected = render(fresh, 1.0);
  ASSERT_FALSE(before.empty() || after.empty() || expected.empty());
  EXPECT_GT(aq::test::max_abs_diff(before, expected, 3), 0.01) << "the paper does not show";
  EXPECT_EQ(aq::test::max_abs_diff(after, expected, 3), 0.0) << "painted on the old paper";
}

}  // namespace
