// The evaluation plan (plan.h): what runs, in which pass, at which size, and what is cached,
// decided before anything runs. These tests need no GL: the plan is a plain value.
#include <gtest/gtest.h>

#include <aquarelle/core/graph_io.h>
#include <aquarelle/core/plan.h>

#include "support/harness.h"

namespace aq::test {
namespace {

// noise -> tint -> vignette -> dim, plus a node nothing reads.
const char* kChain = R"({
  "aquarelle": 1,
  "settings": {"width": 96, "height": 64},
  "nodes": {
    "noise": {"type": "noise", "params": {"scale": 4}},
    "unused": {"type": "noise", "params": {"scale": 8}},
    "tint": {"type": "tint", "params": {"amount": 0.3}, "inputs": {"image": "noise.image"}},
    "vignette": {"type": "vignette", "inputs": {"image": "tint.image"}},
    "dim": {"type": "tint", "params": {"amount": 0.5}, "inputs": {"image": "vignette.image"}}
  },
  "output": "dim.image"
})";

Plan plan_of(const char* text, const std::string& quality = "final", bool fuse = true,
             const std::optional<PortRef>& output = std::nullopt) {
  auto read = read_graph_text(text, registry(), "plan test");
  EXPECT_TRUE(read.ok());
  read.graph.settings.quality = quality;
  PlanOptions options;
  options.fuse_pointwise = fuse;
  auto plan = compile_plan(read.graph, registry(), options, output);
  EXPECT_TRUE(plan.ok()) << plan.message();
  return plan.ok() ? *plan : Plan{};
}

TEST(Plan, CullsWhatTheOutputDoesNotNeedAndSortsInputsFirst) {
  Plan plan = plan_of(kChain);
  std::vector<std::string> order;
  for (const auto& node : plan.nodes) order.push_back(node.id);
  EXPECT_EQ(order, (std::vector<std::string>{"noise", "tint", "vignette", "dim"}));
  EXPECT_EQ(plan.find("unused"), nullptr);
  EXPECT_EQ(plan.pass_of("unused"), nullptr);
}

TEST(Plan, APointwiseChainIsOnePassThatSavesItsIntermediates) {
  Plan plan = plan_of(kChain);
  ASSERT_EQ(plan.passes.size(), 2u);  // noise, then the fused chain
  const PlannedPass& chain = plan.passes[1];
  EXPECT_EQ(chain.node, "dim");
  EXPECT_EQ(chain.chain, (std::vector<std::string>{"tint", "vignette", "dim"}));
  EXPECT_TRUE(chain.fused);
  EXPECT_EQ(chain.reads_per_pixel, 1);
  EXPECT_EQ(chain.intermediates_saved, 2);
  EXPECT_TRUE(plan.find("tint")->deferred);
  EXPECT_FALSE(plan.find("dim")->deferred);
  EXPECT_EQ(plan.pass_of("vignette"), &plan.passes[1]);
  EXPECT_FALSE(plan.upscale) << "final renders at the graph's size";
  EXPECT_EQ(chain.size.width, 96);
}

TEST(Plan, WithoutFusionEveryNodeIsAPass) {
  Plan plan = plan_of(kChain, "final", false);
  ASSERT_EQ(plan.passes.size(), 4u);
  for (const auto& pass : plan.passes) {
    EXPECT_FALSE(pass.fused) << pass.node;
    EXPECT_EQ(pass.chain.size(), 1u);
  }
}

TEST(Plan, ViewingAFusedNodeGivesItAPassOfItsOwn) {
  Plan plan = plan_of(kChain, "final", true, PortRef{"vignette", "image"});
  ASSERT_EQ(plan.passes.size(), 2u);
  EXPECT_EQ(plan.passes[1].chain, (std::vector<std::string>{"tint", "vignette"}));
  EXPECT_EQ(plan.find("dim"), nullptr);
}

TEST(Plan, AProxyRenderRunsTheOutputsTailInsideTheUpscale) {
  Plan plan = plan_of(kChain, "preview");
  EXPECT_EQ(plan.working.width, 48);
  EXPECT_EQ(plan.working.height, 32);
  EXPECT_EQ(plan.passes[0].size.width, 48) << "noise renders at the working size";
  EXPECT_TRUE(plan.passes[1].resamples);
  EXPECT_EQ(plan.passes[1].size.width, 96) << "the tail writes the graph's size";
  EXPECT_FALSE(plan.upscale) << "no separate upscale pass";
  // A proxy render whose output node cannot be fused needs the host's upscale pass.
  Plan plain = plan_of(kChain, "preview", true, PortRef{"noise", "image"});
  EXPECT_TRUE(plain.upscale);
}

TEST(Plan, TheFlagshipGraphCachesWhatIsStatic) {
  auto read = read_graph_file(source_path("graphs/underwater.json"), registry());
  ASSERT_TRUE(read.ok());
  read.graph.settings.quality = "final";
  auto plan = compile_plan(read.graph, registry(), PlanOptions{});
  ASSERT_TRUE(plan.ok()) << plan.message();
  ASSERT_NE(plan->pass_of("paper"), nullptr);
  EXPECT_TRUE(plan->pass_of("paper")->cached) << "the paper does not change over time";
  EXPECT_FALSE(plan->pass_of("gbuf")->cached) << "the fish swim";
  EXPECT_EQ(plan->pass_of("vignette"), plan->pass_of("tint"));
  // The printed plan names every pass.
  const std::string text = format_plan(*plan);
  for (const auto& pass : plan->passes) {
    EXPECT_NE(text.find(pass.node), std::string::npos) << pass.node;
  }
  EXPECT_NE(text.find("epilogue: blur -> vignette -> tint"), std::string::npos) << text;
}

// aq_host::output_read: an output is read when a link of the plan reads it or it is the
// requested output. In the flagship the light reads the g-buffer's `surface` and the blur its
// `depth`, so the other four targets may stay unwritten; viewing one of them makes it read.
TEST(Plan, OutputsAreReadByTheirLinksOrByBeingRequested) {
  auto read = read_graph_file(source_path("graphs/underwater.json"), registry());
  ASSERT_TRUE(read.ok());
  auto plan = compile_plan(read.graph, registry(), PlanOptions{});
  ASSERT_TRUE(plan.ok()) << plan.message();
  const PlannedNode* gbuf = plan->find("gbuf");
  ASSERT_NE(gbuf, nullptr);
  // position, normal, albedo, depth, id, surface
  EXPECT_EQ(gbuf->outputs_read, (std::vector<bool>{false, false, false, true, false, true}));
  EXPECT_EQ(plan->find("tint")->outputs_read, std::vector<bool>{true}) << "the graph's output";
  auto viewed = compile_plan(read.graph, registry(), PlanOptions{}, PortRef{"gbuf", "normal"});
  ASSERT_TRUE(viewed.ok()) << viewed.message();
  EXPECT_EQ(viewed->find("gbuf")->outputs_read,
            (std::vector<bool>{false, true, false, false, false, false}));
}

TEST(Plan, ACycleIsAnErrorNamingItsNodes) {
  const char* cycle = R"({
    "aquarelle": 1,
    "nodes": {
      "a": {"type": "tint", "inputs": {"image": "b.image"}},
      "b": {"type": "tint", "inputs": {"image": "a.image"}}
    },
    "output": "a.image"
  })";
  auto read = read_graph_text(cycle, registry(), "plan test");
  auto plan = compile_plan(read.graph, registry(), PlanOptions{});
  ASSERT_FALSE(plan.ok());
  EXPECT_NE(plan.message().find("cycle"), std::string::npos) << plan.message();
  EXPECT_NE(plan.message().find("a -> b"), std::string::npos) << plan.message();
}

}  // namespace
}  // namespace aq::test
