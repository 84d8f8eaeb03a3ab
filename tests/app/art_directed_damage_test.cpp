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

TEST(ArtDirectedDamage, WindmillAnimatedEqualsEveryFrameFromScratch) {
  expect_animation_equals_scratch("windmill", {"control", "paint"});
}

TEST(ArtDirectedDamage, WaterfallAnimatedEqualsEveryFrameFromScratch) {
  expect_animation_equals_scratch("waterfall", {"control"});
}

}  // namespace
