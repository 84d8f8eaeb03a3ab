// Neighbourhood fusion of separable filters (AQ_PORT_DEFER_AXIS, aq_host::defer_axis): in a
// morphology chain stored in 2 x 2 blocks, a node leaves its last 1D pass to its one reader,
// which runs it in one pass with its own first pass along the same axis (morphology.glsl,
// AQ_MORPH_PENDING_RADIUS): erode -> dilate -> erode takes four passes instead of six. The plan
// tests need no GL; the render tests compare the lever on and off (AQUARELLE_DEFER_AXIS=0): min
// and max of the same stored values, so the same bits, at even, odd and tiny sizes, for every
// pair of radii, and for a requested intermediate (which the plan does not hand on). An
// animation of the flagship with damage tracking is checked in damage_tracking_test.
#include <gtest/gtest.h>

#include <aquarelle/core/graph_io.h>
#include <aquarelle/core/plan.h>
#include <aquarelle/core/registry.h>

#include <cstdlib>
#include <optional>
#include <random>
#include <string>

#include "support/harness.h"
#include "support/morphology_graphs.h"

namespace aq::test {
namespace {

// Every radius from 1 to 4 on both sides of a handed-on pass, a size-1 node (radius 0) that
// takes one over, and a disc, which cannot fuse and runs the pass it was left on its own.
const char* kWideChain = R"({
  "aquarelle": 1,
  "nodes": {
    "input": {"type": "image_input", "params": {"name": "image"}},
    "d3": {"type": "dilate", "params": {"size": 3}, "inputs": {"image": "input.image"}},
    "e9": {"type": "erode", "params": {"size": 9}, "inputs": {"image": "d3.image"}},
    "d7": {"type": "dilate", "params": {"size": 7}, "inputs": {"image": "e9.image"}},
    "e5": {"type": "erode", "params": {"size": 5}, "inputs": {"image": "d7.image"}},
    "one": {"type": "erode", "params": {"size": 1}, "inputs": {"image": "e5.image"}},
    "d9": {"type": "dilate", "params": {"size": 9}, "inputs": {"image": "one.image"}},
    "disc": {"type": "erode", "params": {"size": 5, "footprint": "disc"},
             "inputs": {"image": "d9.image"}},
    "last": {"type": "dilate", "params": {"size": 3}, "inputs": {"image": "disc.image"}}
  },
  "output": "last.image"
})";

Plan plan_of(const std::string& text, const std::string& precision,
             const std::optional<PortRef>& output = std::nullopt) {
  const ReadResult read = read_graph_text(text, registry(), "chain");
  EXPECT_TRUE(read.ok());
  Graph graph = read.graph;
  graph.settings.precision = precision;
  auto plan = compile_plan(graph, registry(), PlanOptions{}, output);
  EXPECT_TRUE(plan.ok()) << plan.message();
  return plan.ok() ? *plan : Plan{};
}

bool hands_on(const Plan& plan, const std::string& id) {
  const PlannedNode* node = plan.find(id);
  return node != nullptr && !node->axis_deferrable.empty() && node->axis_deferrable[0];
}

// Random HDR colours (the morphology compares encoded 8-bit values), with edges to move.
ImageF random_light(int width, int height, unsigned seed) {
  ImageF image(width, height, 4, 1.0f);
  std::mt19937 random(seed);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x)
      for (int c = 0; c < 3; ++c)
        image.at(x, y, c) = static_cast<float>(4.0 * unit(random) * unit(random));
  return image;
}

Result<ImageF> render(const std::string& graph, const ImageF& input, bool hand_on,
                      const std::string& output = "") {
  if (!hand_on) setenv("AQUARELLE_DEFER_AXIS", "0", 1);
  RenderOptions options;
  options.width = input.width;
  options.height = input.height;
  options.precision = "half";
  options.output = output;
  auto image = render_graph(graph, options, {{"image", input}});
  unsetenv("AQUARELLE_DEFER_AXIS");
  return image;
}

TEST(AxisFusion, ThePlanHandsALastPassOnlyToTheOneReaderThatTakesIt) {
  const Plan plan = plan_of(kMorphologyChain, "half");
  EXPECT_TRUE(hands_on(plan, "open_erode"));
  EXPECT_TRUE(hands_on(plan, "dilate"));
  EXPECT_FALSE(hands_on(plan, "close_erode")) << "the requested output is whole";
  EXPECT_NE(format_plan(plan).find("[last 1D pass to its reader: image]"), std::string::npos);

  // Viewing an intermediate (the editor, --layer) makes it whole.
  const Plan viewed = plan_of(kMorphologyChain, "half", PortRef{"dilate", "image"});
  EXPECT_TRUE(hands_on(viewed, "open_erode"));
  EXPECT_FALSE(hands_on(viewed, "dilate"));

  // A second reader (edge's `source`, which takes pixels): the output is whole for both.
  const std::string two = R"({
    "aquarelle": 1,
    "nodes": {
      "input": {"type": "image_input", "params": {"name": "image"}},
      "open_erode": {"type": "erode", "params": {"size": 3}, "inputs": {"image": "input.image"}},
      "dilate": {"type": "dilate", "params": {"size": 5}, "inputs": {"image": "open_erode.image"}},
      "edge": {"type": "edge", "inputs": {"image": "dilate.image", "source": "open_erode.image"}}
    },
    "output": "edge.image"
  })";
  const Plan shared = plan_of(two, "half");
  EXPECT_FALSE(hands_on(shared, "open_erode"));
  EXPECT_FALSE(hands_on(shared, "dilate")) << "edge does not take blocks";

  // Float precision stores no blocks: nothing is handed on.
  const Plan full = plan_of(kMorphologyChain, "float");
  EXPECT_FALSE(hands_on(full, "open_erode"));
  EXPECT_FALSE(hands_on(full, "dilate"));
}

TEST(AxisFusion, HandedOnPassesGiveTheSameBitsAsPassesInTheirOwnNodes) {
  const Plan plan = plan_of(kWideChain, "half");
  for (const char* id : {"d3", "e9", "d7", "e5", "d9"}) EXPECT_TRUE(hands_on(plan, id)) << id;
  for (const char* graph : {kMorphologyChain, kWideChain}) {
    for (const auto& [width, height] : {std::pair{64, 48}, {63, 47}, {17, 9}, {5, 3}}) {
      const ImageF light = random_light(width, height, 11);
      auto whole = render(graph, light, false);
      // Another image in between: the nodes keep their outputs (damage tracking), so the same
      // input again would be answered without drawing.
      ASSERT_TRUE(render(graph, random_light(width, height, 12), true).ok());
      auto handed = render(graph, light, true);
      ASSERT_TRUE(whole.ok()) << whole.message();
      ASSERT_TRUE(handed.ok()) << handed.message();
      EXPECT_EQ(max_abs_diff(*handed, *whole), 0.0) << width << "x" << height;
      EXPECT_GT(max_abs_diff(*handed, light), 0.0) << "the windows moved nothing";
    }
  }
}

TEST(AxisFusion, ARequestedIntermediateIsWhole) {
  const ImageF light = random_light(40, 30, 5);
  for (const char* output : {"open_erode.image", "dilate.image"}) {
    auto whole = render(kMorphologyChain, light, false, output);
    ASSERT_TRUE(render(kMorphologyChain, random_light(40, 30, 6), true, output).ok());
    auto viewed = render(kMorphologyChain, light, true, output);
    ASSERT_TRUE(whole.ok()) << whole.message();
    ASSERT_TRUE(viewed.ok()) << viewed.message();
    EXPECT_EQ(max_abs_diff(*viewed, *whole), 0.0) << output;
  }
}

// Issue 38 item 5: a chain fed by the light's 8-bit HDR image (so it runs in blocks and hands
// its passes on) and ending the graph: the last erode takes a pending rows pass and writes
// pixels. Its columns pass reads blocks and writes pixels (the plain blocked columns pass, not
// the blocks-to-blocks one, which declares no o_color): it compiles, renders, and gives the
// bits of the passes run in their own nodes.
TEST(AxisFusion, AChainThatEndsTheGraphAfterTheLightRenders) {
  const std::string graph = R"({
    "aquarelle": 1,
    "nodes": {
      "scene": {"type": "scene", "params": {"preset": "plane_box"}},
      "gbuf": {"type": "gbuffer", "inputs": {"scene": "scene.scene"}},
      "light": {"type": "cel_light", "inputs": {"scene": "scene.scene",
                "surface": "gbuf.surface"}},
      "open_erode": {"type": "erode", "params": {"size": 3}, "inputs": {"image": "light.image"}},
      "dilate": {"type": "dilate", "params": {"size": 5}, "inputs": {"image": "open_erode.image"}},
      "close_erode": {"type": "erode", "params": {"size": 3}, "inputs": {"image": "dilate.image"}}
    },
    "output": "close_erode.image"
  })";
  const Plan plan = plan_of(graph, "half");
  EXPECT_TRUE(hands_on(plan, "open_erode"));
  EXPECT_TRUE(hands_on(plan, "dilate"));
  for (const auto& [width, height] : {std::pair{64, 48}, {37, 21}}) {
    RenderOptions options;
    options.width = width;
    options.height = height;
    options.precision = "half";
    setenv("AQUARELLE_DEFER_AXIS", "0", 1);
    auto whole = render_graph(graph, options);
    unsetenv("AQUARELLE_DEFER_AXIS");
    auto handed = render_graph(graph, options);
    ASSERT_TRUE(whole.ok()) << whole.message();
    ASSERT_TRUE(handed.ok()) << handed.message();
    EXPECT_EQ(max_abs_diff(*handed, *whole), 0.0) << width << "x" << height;
  }
}

}  // namespace
}  // namespace aq::test
