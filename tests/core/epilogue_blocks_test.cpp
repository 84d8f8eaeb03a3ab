// An epilogue producer writing 2 x 2 blocks (AQ_PORT_BLOCKS on its output, aq_epilogue_at): the
// wobble with the pointwise nodes after it fused into its draw writes the chain's result in
// blocks when every reader takes them (the blur), four pixels a fragment. The plan test needs no
// GL; the render tests compare the lever on and off (AQUARELLE_EPILOGUE_BLOCKS=0: the same chain
// written as encoded pixels): the same pixels wobbled, passed through the epilogue at their own
// centres and encoded, so the same bits, at even, odd and tiny sizes, for the blur's separable
// kernel (which reads the blocks), its other methods and σ = 0 (which decode them first). The
// flagship's animation with damage tracking is checked in damage_tracking_test.
#include <gtest/gtest.h>

#include <aquarelle/core/graph_io.h>
#include <aquarelle/core/plan.h>
#include <aquarelle/core/registry.h>

#include <cstdlib>
#include <string>

#include "support/harness.h"

namespace aq::test {
namespace {

// wobble -> vignette (fused into the wobble's draw) -> blur (depth-free but varying strength, so
// the direct kernels run) with `blur_params`.
std::string chain(const std::string& blur_params) {
  return R"({
    "aquarelle": 1,
    "nodes": {
      "input": {"type": "image_input", "params": {"name": "image"}},
      "wobble": {"type": "wobble", "params": {"strength": 8.0, "paper_resolution": 64},
                 "inputs": {"image": "input.image"}},
      "vignette": {"type": "vignette", "inputs": {"image": "wobble.image"}},
      "blur": {"type": "blur", "params": )" +
         blur_params + R"(, "inputs": {"image": "vignette.image"}}
    },
    "output": "blur.image"
  })";
}

const std::string kSeparable = R"({"sigma": 2.0, "depth_weight": 0.4, "radial_weight": 0.35})";

uint32_t stored_format(const Plan& plan, const std::string& id) {
  const PlannedNode* node = plan.find(id);
  return node == nullptr || node->stored_formats.empty() ? 0 : node->stored_formats[0];
}

Result<ImageF> render(const std::string& graph, const ImageF& input, bool blocks) {
  if (!blocks) setenv("AQUARELLE_EPILOGUE_BLOCKS", "0", 1);
  RenderOptions options;
  options.width = input.width;
  options.height = input.height;
  options.precision = "half";
  auto image = render_graph(graph, options, {{"image", input}});
  unsetenv("AQUARELLE_EPILOGUE_BLOCKS");
  return image;
}

TEST(EpilogueBlocks, TheWobblesChainIsStoredInBlocksOnlyWhereItsReaderTakesThem) {
  const ReadResult read = read_graph_text(chain(kSeparable), registry(), "chain");
  ASSERT_TRUE(read.ok());
  Graph graph = read.graph;
  graph.settings.precision = "half";
  auto plan = compile_plan(graph, registry(), PlanOptions{});
  ASSERT_TRUE(plan.ok()) << plan.message();
  EXPECT_EQ(stored_format(*plan, "vignette"), AQ_FORMAT_RGBA8_HDR_BLOCKS) << format_plan(*plan);

  PlanOptions pixels;
  pixels.epilogue_blocks = false;
  auto unblocked = compile_plan(graph, registry(), pixels);
  ASSERT_TRUE(unblocked.ok());
  EXPECT_EQ(stored_format(*unblocked, "vignette"), AQ_FORMAT_RGBA8_HDR);

  // A second reader that takes pixels (edge's `source`) keeps the chain in pixels.
  const ReadResult shared_read = read_graph_text(
      R"({"aquarelle": 1, "nodes": {
        "input": {"type": "image_input", "params": {"name": "image"}},
        "wobble": {"type": "wobble", "inputs": {"image": "input.image"}},
        "vignette": {"type": "vignette", "inputs": {"image": "wobble.image"}},
        "blur": {"type": "blur", "params": {"sigma": 2.0, "radial_weight": 0.35},
                 "inputs": {"image": "vignette.image"}},
        "edge": {"type": "edge", "inputs": {"image": "blur.image", "source": "vignette.image"}}},
        "output": "edge.image"})",
      registry(), "shared");
  ASSERT_TRUE(shared_read.ok());
  Graph shared = shared_read.graph;
  shared.settings.precision = "half";
  auto shared_plan = compile_plan(shared, registry(), PlanOptions{});
  ASSERT_TRUE(shared_plan.ok()) << shared_plan.message();
  EXPECT_NE(stored_format(*shared_plan, "vignette"), AQ_FORMAT_RGBA8_HDR_BLOCKS);
}

TEST(EpilogueBlocks, BlocksGiveTheSameBitsAsEncodedPixels) {
  const std::string graphs[] = {
      chain(kSeparable),
      chain(R"({"sigma": 2.0, "depth_weight": 0.4, "radial_weight": 0.35, "method": "strided"})"),
      chain(R"({"sigma": 2.0, "depth_weight": 0.4, "radial_weight": 0.35,
                "direct_kernel": "full"})"),
      chain(R"({"sigma": 0.0})")};
  for (const std::string& graph : graphs) {
    for (const auto& [width, height] : {std::pair{64, 48}, {63, 47}, {17, 9}, {5, 3}}) {
      const ImageF light = random_image(width, height, 21, 0.0f, 4.0f);
      auto pixels = render(graph, light, false);
      auto blocks = render(graph, light, true);
      ASSERT_TRUE(pixels.ok()) << pixels.message();
      ASSERT_TRUE(blocks.ok()) << blocks.message();
      EXPECT_EQ(max_abs_diff(*blocks, *pixels), 0.0) << width << "x" << height << "\n" << graph;
      EXPECT_GT(max_abs_diff(*blocks, light), 0.0) << "the chain changed nothing";
    }
  }
}

}  // namespace
}  // namespace aq::test
