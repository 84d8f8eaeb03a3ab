// Damage tracking (aq_host::input_damage, set_output_damage, set_draw_region, output bounds):
// nodes whose outputs the host kept redraw only the pixels that can have changed. An animation
// of the flagship graph evaluated frame after frame, as `aquarelle render` does, must give the
// very pixels of each frame evaluated from scratch (every node new, nothing kept), also when a
// parameter of the light, of the wobble (an epilogue producer) or of edge (a fused stage)
// changes on the way; and the redraw must really be partial once the outputs are kept.
#include <aquarelle/core/evaluator.h>
#include <aquarelle/core/gl_context.h>
#include <aquarelle/core/graph_io.h>
#include <aquarelle/core/plugin_loader.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cstdlib>
#include <map>
#include <string>

#include "support/harness.h"

namespace {

using aq::ImageF;

aq::Graph flagship(const std::string& precision) {
  aq::ReadResult read =
      aq::read_graph_file(aq::test::source_path("graphs/underwater.json"), aq::test::registry());
  EXPECT_TRUE(read.ok());
  aq::Graph graph = read.graph;
  graph.settings.width = 192;
  graph.settings.height = 108;
  graph.settings.quality = "final";
  graph.settings.precision = precision;
  return graph;
}

// The graph as frame `frame` sees it: parameters change at frames 5, 6 and 7.
aq::Graph at_frame(aq::Graph graph, int frame) {
  if (frame >= 5) graph.nodes.at("edges").params["threshold"] = 0.25;
  if (frame >= 6) graph.nodes.at("wobble").params["strength"] = 5.0;
  if (frame >= 7) graph.nodes.at("light").params["levels"] = 3;
  return graph;
}

ImageF evaluate(aq::Evaluator& evaluator, const aq::Graph& graph, int frame) {
  aq::EvalOptions options;
  options.frame = frame;
  options.retain_outputs = false;  // as `aquarelle render`: outputs go back to the pool
  options.retain_static_outputs = true;
  auto texture = evaluator.evaluate(graph, options);
  EXPECT_TRUE(texture.ok()) << texture.message();
  if (!texture.ok()) return ImageF();
  auto pixels = evaluator.read_back(*texture);
  EXPECT_TRUE(pixels.ok()) << pixels.message();
  return pixels.ok() ? *pixels : ImageF();
}

double redrawn(const aq::Evaluator& evaluator, const std::string& node) {
  for (const aq::NodeTiming& timing : evaluator.last_timings())
    if (timing.node == node && !timing.cached && !timing.fused) return timing.redrawn;
  return -2.0;  // did not run
}

// Scratch images arrive full of junk (AQUARELLE_POISON_SCRATCH): a pass reading pixels that no
// pass of its call wrote differs from the frame from scratch instead of reading last frame's.
struct PoisonedScratch {
  PoisonedScratch() { setenv("AQUARELLE_POISON_SCRATCH", "1", 1); }
  ~PoisonedScratch() { unsetenv("AQUARELLE_POISON_SCRATCH"); }
};

TEST(DamageTracking, AnAnimationEqualsEveryFrameFromScratch) {
  const PoisonedScratch poisoned;
  auto context = aq::create_headless_context(aq::GlBackend::kAuto);
  ASSERT_TRUE(context.ok()) << context.message();
  for (const std::string precision : {"float", "half"}) {
    const aq::Graph base = flagship(precision);
    aq::Evaluator animated(**context, aq::test::registry());
    aq::Evaluator scratch(**context, aq::test::registry());
    ImageF previous;
    for (int frame = 1; frame <= 8; ++frame) {
      const aq::Graph graph = at_frame(base, frame);
      const ImageF got = evaluate(animated, graph, frame);
      scratch.clear();  // every node new: nothing kept, everything drawn
      const ImageF expected = evaluate(scratch, graph, frame);
      ASSERT_FALSE(got.empty());
      ASSERT_FALSE(expected.empty());
      EXPECT_EQ(aq::test::max_abs_diff(got, expected), 0.0) << precision << ", frame " << frame;
      if (!previous.empty()) {
        EXPECT_GT(aq::test::max_abs_diff(got, previous), 0.0)
            << "frame " << frame << ": nothing moved, the test would prove nothing";
      }
      previous = got;
      // The pool hands the outputs back from the third frame on (they are tagged once the
      // nodes asked); from then on the g-buffer, the shadow map (their moving meshes) and the
      // nodes downstream of the light redraw part of the frame while only the animation changed
      // (frame 4), all of it after a parameter changed.
      if (frame == 4) {
        for (const char* node : {"gbuf", "shadow", "light", "open_erode", "dilate", "close_erode",
                                 "pigment", "tint"}) {
          const double share = redrawn(animated, node);
          EXPECT_GT(share, 0.0) << node << " at frame 4 (" << precision << ")";
          EXPECT_LT(share, 0.95) << node << " at frame 4 redrew everything (" << precision << ")";
        }
      }
      // The light redraws the g-buffer's bounds (the caustics move on every surface): the tiles
      // its meshes' triangles cover, 69.6 % of this frame; the meshes' boxes covered 72.6 %
      // (a seaweed cluster's box spans the water between its blades). Its `plain` regions
      // change only with the g-buffer, so the light's share is the mean of two; open_erode
      // redraws its image's damage widened by one pixel (68.5 %).
      if (frame == 4) {
        EXPECT_LT(redrawn(animated, "open_erode"), 0.71)
            << "the g-buffer's bounds (" << precision << ")";
        // The edges follow the objects' regions, which move only with the g-buffer, not with
        // the caustics that make the light redraw every surface.
        EXPECT_LT(redrawn(animated, "edges"), 0.5 * redrawn(animated, "open_erode"))
            << "the regions' edges redrawn where the light changed (" << precision << ")";
      }
      if (frame == 7) {
        EXPECT_EQ(redrawn(animated, "light"), 1.0) << "light.levels changed";
      }
    }
  }
}

// The real plugins and the test nodes (test_square) in one registry.
const aq::Registry& registry_with_test_nodes() {
  static aq::Registry* registry = [] {
    auto* r = new aq::Registry();
    static aq::PluginSet plugins;
    aq::register_builtin_nodes(*r);
    plugins.load({AQ_PLUGIN_BUILD_DIR}, *r);
    std::string why;
    EXPECT_TRUE(
        plugins.load_file(std::string(AQ_TEST_PLUGIN_DIR) + "/aquarelle_test_nodes.so", *r, &why))
        << why;
    return r;
  }();
  return *registry;
}

// A square moving by 5 pixels a frame through every kind of node that keeps its output: the
// morphology (each window widens what changed), the wobble with edge and pigment_apply fused
// into its draw (its reach, the edge's 3x3 source), the blur with vignette and tint fused. Each
// frame equals the frame from scratch exactly, and the nodes redraw a small part of it. (A
// morphology that forgets its window's reach fails the first half; the wobble's reach is a
// bound by construction, its slope clamped to 1, far above what the cells move it here.)
TEST(DamageTracking, AMovingSquareThroughStencilsAndEpiloguesEqualsFromScratch) {
  const PoisonedScratch poisoned;
  auto context = aq::create_headless_context(aq::GlBackend::kAuto);
  ASSERT_TRUE(context.ok()) << context.message();
  const nlohmann::json graph_json = {
      {"aquarelle", 1},
      {"settings", {{"width", 128}, {"height", 72}, {"quality", "final"}, {"precision", "float"}}},
      {"nodes",
       {{"square", {{"type", "test_square"}}},
        {"open",
         {{"type", "erode"}, {"params", {{"size", 3}}}, {"inputs", {{"image", "square.image"}}}}},
        {"grow",
         {{"type", "dilate"}, {"params", {{"size", 5}}}, {"inputs", {{"image", "open.image"}}}}},
        {"paper", {{"type", "paper"}, {"params", {{"seed", 3}}}}},
        // Worley cells as the paper: steep slopes, the lookups move.
        {"cells",
         {{"type", "noise"}, {"params", {{"type", "worley"}, {"scale", 64}, {"seed", 3}}}}},
        {"wobble",
         {{"type", "wobble"},
          {"params", {{"strength", 12.0}}},
          {"inputs", {{"image", "grow.image"}, {"paper", "cells.image"}}}}},
        {"edge",
         {{"type", "edge"}, {"inputs", {{"image", "wobble.image"}, {"source", "square.image"}}}}},
        {"canvas", {{"type", "pigment_canvas"}, {"inputs", {{"paper", "paper.image"}}}}},
        {"pigment",
         {{"type", "pigment_apply"},
          {"inputs", {{"image", "edge.image"}, {"density", "canvas.density"}}}}},
        {"blur",
         {{"type", "blur"},
          {"params", {{"sigma", 2.0}, {"depth_weight", 0.3}, {"radial_weight", 0.5}}},
          {"inputs", {{"image", "pigment.image"}}}}},
        {"vignette", {{"type", "vignette"}, {"inputs", {{"image", "blur.image"}}}}},
        {"tint", {{"type", "tint"}, {"inputs", {{"image", "vignette.image"}}}}}}},
      {"output", "tint.image"}};
  aq::ReadResult read =
      aq::read_graph_text(graph_json.dump(), registry_with_test_nodes(), "square graph");
  ASSERT_TRUE(read.ok()) << aq::format_problems(read.problems);
  aq::Evaluator animated(**context, registry_with_test_nodes());
  aq::Evaluator scratch(**context, registry_with_test_nodes());
  for (int frame = 1; frame <= 12; ++frame) {
    const ImageF got = evaluate(animated, read.graph, frame);
    scratch.clear();
    const ImageF expected = evaluate(scratch, read.graph, frame);
    ASSERT_FALSE(got.empty());
    EXPECT_EQ(aq::test::max_abs_diff(got, expected), 0.0) << "frame " << frame;
    if (frame >= 4) {
      for (const char* node : {"square", "open", "grow", "pigment", "tint"}) {
        const double share = redrawn(animated, node);
        EXPECT_GT(share, 0.0) << node << " at frame " << frame;
        EXPECT_LT(share, 0.5) << node << " at frame " << frame << " redrew too much";
      }
    }
  }
}

// A draw region of 40 rects (test_rects): the host draws up to 16 rects per instanced draw
// where the program is its full-screen one (each instance in its viewport's scissor box), and
// one draw per rect where the node brought its own vertex shader. Either way every rect is
// drawn, in full, and nothing outside them.
TEST(DamageTracking, EveryRectOfADrawRegionIsDrawnAndNothingElse) {
  auto context = aq::create_headless_context(aq::GlBackend::kAuto);
  ASSERT_TRUE(context.ok()) << context.message();
  for (bool own_vertex : {false, true}) {
    const nlohmann::json graph_json = {
        {"aquarelle", 1},
        {"settings", {{"width", 48}, {"height", 32}, {"precision", "float"}}},
        {"nodes", {{"rects", {{"type", "test_rects"}, {"params", {{"own_vertex", own_vertex}}}}}}},
        {"output", "rects.image"}};
    aq::ReadResult read =
        aq::read_graph_text(graph_json.dump(), registry_with_test_nodes(), "rects graph");
    ASSERT_TRUE(read.ok()) << aq::format_problems(read.problems);
    aq::Evaluator evaluator(**context, registry_with_test_nodes());
    const ImageF got = evaluate(evaluator, read.graph, 1);
    ASSERT_EQ(got.width, 48);
    ASSERT_EQ(got.height, 32);
    int wrong = 0;
    for (int y = 0; y < got.height; ++y) {
      for (int x = 0; x < got.width; ++x) {
        const bool inside = x < 40 && y < 24 && x % 4 >= 1 && x % 4 < 3 && y % 6 >= 1 && y % 6 < 4;
        const float expected = inside ? 1.0f : 0.25f;
        for (int c = 0; c < 3; ++c) wrong += got.at(x, y, c) != expected ? 1 : 0;
      }
    }
    EXPECT_EQ(wrong, 0) << (own_vertex ? "own vertex shader" : "host's full-screen triangle");
  }
}

}  // namespace
