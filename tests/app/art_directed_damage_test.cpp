// Damage tracking in the art-directed graphs (issue 35's speed): control_map keeps a cached
// layer of the meshes that did not move, and dilution, bleed, edge_darkening, tremor and clouds
// redraw only the pixels that can have changed. Each graph animated frame after frame, as
// `aquarelle render` does (outputs kept), must give the very pixels of each frame evaluated
// from scratch (every node new, nothing kept: the exact nodes), and the redraw must really be
// partial once the outputs are kept.
#include <aquarelle/core/evaluator.h>
#include <aquarelle/core/gl_context.h>
#include <aquarelle/core/graph_io.h>
#include <gtest/gtest.h>

#include <cstdio>
#include <optional>
#include <string>
#include <vector>

#include "support/harness.h"

namespace {

using aq::ImageF;

aq::Graph small_graph(const std::string& name) {
  aq::ReadResult read =
      aq::read_graph_file(aq::test::source_path("graphs/" + name + ".json"), aq::test::registry());
  EXPECT_TRUE(read.ok()) << name;
  aq::Graph graph = read.graph;
  graph.settings.width = 256;
  graph.settings.height = 144;
  graph.settings.quality = "final";
  return graph;
}

ImageF evaluate(aq::Evaluator& evaluator, const aq::Graph& graph, int frame,
                const std::optional<aq::PortRef>& port = std::nullopt) {
  aq::EvalOptions options;
  options.frame = frame;
  options.retain_outputs = false;  // as `aquarelle render`: outputs go back to the pool
  options.retain_static_outputs = true;
  auto texture = evaluator.evaluate(graph, options, port);
  EXPECT_TRUE(texture.ok()) << texture.message();
  if (!texture.ok()) return ImageF();
  auto pixels = evaluator.read_back(*texture);
  EXPECT_TRUE(pixels.ok()) << pixels.message();
  return pixels.ok() ? *pixels : ImageF();
}

// The share of the node's outputs it redrew on the last frame (-2: it did not run itself).
double redrawn(const aq::Evaluator& evaluator, const std::string& node) {
  for (const aq::NodeTiming& timing : evaluator.last_timings())
    if (timing.node == node && !timing.cached && !timing.fused) return timing.redrawn;
  return -2.0;
}

// Frames 1..6 animated against from scratch; at frame 5 the named nodes redrew part only.
void expect_animation_equals_scratch(const std::string& name,
                                     const std::vector<std::string>& partial) {
  auto context = aq::create_headless_context(aq::GlBackend::kAuto);
  ASSERT_TRUE(context.ok()) << context.message();
  const aq::Graph graph = small_graph(name);
  aq::Evaluator animated(**context, aq::test::registry());
  aq::Evaluator scratch(**context, aq::test::registry());
  ImageF previous;
  for (int frame = 1; frame <= 6; ++frame) {
    const ImageF got = evaluate(animated, graph, frame);
    scratch.clear();  // every node new: nothing kept, everything drawn
    const ImageF expected = evaluate(scratch, graph, frame);
    ASSERT_FALSE(got.empty());
    ASSERT_FALSE(expected.empty());
    EXPECT_EQ(aq::test::max_abs_diff(got, expected), 0.0) << name << ", frame " << frame;
    if (!previous.empty()) {
      EXPECT_GT(aq::test::max_abs_diff(got, previous), 0.0)
          << name << ", frame " << frame << ": nothing moved, the test would prove nothing";
    }
    previous = got;
    if (frame == 5) {
      for (const aq::NodeTiming& timing : animated.last_timings())
        std::printf("%s %s: redrew %.3f%s%s\n", name.c_str(), timing.node.c_str(), timing.redrawn,
                    timing.cached ? " (cached)" : "", timing.fused ? " (fused)" : "");
      for (const std::string& node : partial) {
        const double share = redrawn(animated, node);
        EXPECT_GT(share, 0.0) << name << ": " << node << " at frame 5";
        EXPECT_LT(share, 0.9) << name << ": " << node << " at frame 5 redrew everything";
      }
    }
  }
}

TEST(ArtDirectedDamage, ArtDirectedAnimatedEqualsEveryFrameFromScratch) {
  expect_animation_equals_scratch("art_directed",
                                  {"control", "paint", "bleeding", "edges", "wobble"});
}

// The sky's clouds (a height falloff) drift everywhere above the ramp's start, but below the
// horizon no ray reaches it: the fused clouds + paper relief pass ("relief") redraws only the
// sky's cells and what the tremor changed (the whole frame every frame before).
TEST(ArtDirectedDamage, WindmillAnimatedEqualsEveryFrameFromScratch) {
  expect_animation_equals_scratch("windmill", {"control", "paint", "relief"});
}

TEST(ArtDirectedDamage, WaterfallAnimatedEqualsEveryFrameFromScratch) {
  expect_animation_equals_scratch("waterfall", {"control", "gbuf", "paint"});
}

// The waterfall's cliff and fall tremble, but are seen nearly head-on: hand_tremor hands their
// head-on triangles on unchanged, so the renderers redraw only the silhouettes' strips, not the
// cliff (0.45 of the frame at 640x360 before, 0.25 now).
TEST(ArtDirectedDamage, WaterfallRedrawsOnlyTheTremblingSilhouettes) {
  auto context = aq::create_headless_context(aq::GlBackend::kAuto);
  ASSERT_TRUE(context.ok()) << context.message();
  aq::Graph graph = small_graph("waterfall");
  graph.settings.width = 640;  // at 256x144 the strips' rounding to 16 px blocks hides it
  graph.settings.height = 360;
  aq::Evaluator animated(**context, aq::test::registry());
  for (int frame = 1; frame <= 4; ++frame) evaluate(animated, graph, frame);
  for (const char* node : {"gbuf", "control", "paint"}) {
    const double share = redrawn(animated, node);
    EXPECT_GT(share, 0.0) << node;
    EXPECT_LT(share, 0.35) << node << " redrew the trembling objects whole";
  }
}

// The nodes whose cells are kept between frames, animated (frames 1..4, the kept cells redrawn
// only where the fish moved), against the same node at its exact setting (`resolution 1`) on
// the same frame from a fresh evaluator: the cells' own error, no more (a kept texture sampled
// with other filtering or wrapping than the pool's, as a first version did, is 0.1 and more at
// the borders).
void expect_kept_cells_stay_near_exact(const std::string& node, double max_error,
                                       double mean_error) {
  auto context = aq::create_headless_context(aq::GlBackend::kAuto);
  ASSERT_TRUE(context.ok()) << context.message();
  const aq::Graph graph = small_graph("art_directed");
  aq::Graph exact = graph;
  exact.nodes.at(node).params["resolution"] = 1;
  const aq::PortRef port{node, "image"};
  aq::Evaluator animated(**context, aq::test::registry());
  ImageF got;
  for (int frame = 1; frame <= 4; ++frame) got = evaluate(animated, graph, frame, port);
  aq::Evaluator scratch(**context, aq::test::registry());
  const ImageF want = evaluate(scratch, exact, 4, port);
  ASSERT_FALSE(got.empty());
  ASSERT_FALSE(want.empty());
  const double error = aq::test::max_abs_diff(got, want);
  const double mean = aq::test::mean_abs_diff(got, want);
  std::printf("%s against resolution 1: max abs %.4g, mean abs %.4g\n", node.c_str(), error, mean);
  EXPECT_LE(error, max_error) << node;
  EXPECT_LE(mean, mean_error) << node;
}

TEST(ArtDirectedDamage, KeptBleedCellsStayNearTheExactNode) {
  // The bleed's cells differ most along borders (bench: mean 0.0016, max 0.68 at 1280x720).
  expect_kept_cells_stay_near_exact("bleeding", 1.0, 0.01);
}

TEST(ArtDirectedDamage, KeptEdgeCellsStayNearTheExactNode) {
  expect_kept_cells_stay_near_exact("edges", 0.03, 5e-4);
}

}  // namespace
