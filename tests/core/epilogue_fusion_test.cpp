// Epilogue fusion (plugin.h, AQ_NODE_EPILOGUE): the pointwise chain that alone reads a
// producer's output 0 runs inside the producer's last draw. Fused must equal unfused within
// 1e-6 in float whatever the producer's method does: its shaders apply the chain, or it passes
// its input through / draws with shaders that do not, and the host runs the chain itself.
#include <gtest/gtest.h>

#include <aquarelle/core/evaluator.h>
#include <aquarelle/core/gl_context.h>
#include <aquarelle/core/graph_io.h>
#include <aquarelle/core/plan.h>
#include <aquarelle/core/registry.h>

#include <string>

#include "support/harness.h"

namespace aq::test {
namespace {

// The flagship's tail: blur with a radial σ up to 2 px, then vignette and tint.
std::string tail_graph(const std::string& blur_params) {
  return R"({
  "aquarelle": 1,
  "nodes": {
    "input": {"type": "image_input", "params": {"name": "image"}},
    "blur": {"type": "blur", "params": )" +
         blur_params + R"(, "inputs": {"image": "input.image"}},
    "vignette": {"type": "vignette", "inputs": {"image": "blur.image"}},
    "tint": {"type": "tint", "params": {"amount": 0.2}, "inputs": {"image": "vignette.image"}}
  },
  "output": "tint.image"
})";
}

const std::string kSeparable =
    R"({"sigma": 2.0, "depth_weight": 0.5, "radial_weight": 0.35, "direct_kernel": "separable"})";

RenderOptions options(bool fuse, const char* quality = "final") {
  RenderOptions o;
  o.width = 96;
  o.height = 64;
  o.quality = quality;
  o.fuse_pointwise = fuse;
  return o;
}

std::map<std::string, ImageF> input_images() {
  return {{"image", random_image(96, 64, 5, 0.0f, 3.0f)}};
}

Plan plan_of(const std::string& text, const char* quality = "final",
             const std::optional<PortRef>& output = std::nullopt) {
  auto read = read_graph_text(text, registry(), "epilogue test");
  EXPECT_TRUE(read.ok());
  Graph graph = read.graph;
  graph.settings.width = 96;
  graph.settings.height = 64;
  graph.settings.quality = quality;
  auto plan = compile_plan(graph, registry(), PlanOptions{}, output);
  EXPECT_TRUE(plan.ok()) << plan.message();
  return plan.ok() ? *plan : Plan{};
}

TEST(EpilogueFusion, TheTailRunsInTheBlursLastDraw) {
  const Plan plan = plan_of(tail_graph(kSeparable));
  const PlannedPass* pass = plan.pass_of("tint");
  ASSERT_NE(pass, nullptr);
  EXPECT_TRUE(pass->epilogue);
  EXPECT_EQ(pass->chain, (std::vector<std::string>{"blur", "vignette", "tint"}));
  ASSERT_NE(plan.find("blur"), nullptr);
  EXPECT_TRUE(plan.find("blur")->producer);
  EXPECT_EQ(plan.passes.size(), 2u) << "input, then the blur with its epilogue";
}

TEST(EpilogueFusion, NotInAProxyRenderNorWhenTheBlurIsViewed) {
  // A proxy's tail runs inside the upscale; the viewed blur is its own output.
  EXPECT_FALSE(plan_of(tail_graph(kSeparable), "preview").pass_of("tint")->epilogue);
  const Plan viewed = plan_of(tail_graph(kSeparable), "final", PortRef{"blur", "image"});
  EXPECT_EQ(viewed.find("blur")->producer, false);
}

// The separable kernel and the one-pass kernel call aq_epilogue; strided does not and σ = 0
// passes the input through: the host runs the chain for those.
TEST(EpilogueFusion, FusedEqualsUnfusedForEveryBlurMethod) {
  for (const std::string& params :
       {kSeparable,
        std::string(R"({"sigma": 1.0, "radial_weight": 0.35, "direct_kernel": "full"})"),
        std::string(R"({"method": "strided", "sigma": 2.0})"), std::string(R"({"sigma": 0.0})")}) {
    RenderOptions fused = options(true);
    fused.precision = "float";
    RenderOptions unfused = options(false);
    unfused.precision = "float";
    auto a = render_graph(tail_graph(params), fused, input_images());
    auto b = render_graph(tail_graph(params), unfused, input_images());
    ASSERT_TRUE(a.ok()) << params << ": " << a.message();
    ASSERT_TRUE(b.ok()) << params << ": " << b.message();
    EXPECT_LE(max_abs_diff(*a, *b), 1e-6) << params;
    EXPECT_GT(max_abs_diff(*a, input_images().at("image")), 0.05) << params << ": did nothing";
  }
}

TEST(EpilogueFusion, TheBlurRunsOnceAndTheTailNever) {
  auto read = read_graph_text(tail_graph(kSeparable), registry(), "epilogue test");
  ASSERT_TRUE(read.ok());
  auto context = create_headless_context(GlBackend::kAuto);
  ASSERT_TRUE(context.ok()) << context.message();
  Evaluator evaluator(**context, registry());
  auto images = input_images();
  EvalOptions eval;
  eval.images = &images;
  auto out = evaluator.evaluate(read.graph, eval);
  ASSERT_TRUE(out.ok()) << out.message();
  std::map<std::string, NodeTiming> timing;
  for (const auto& t : evaluator.last_timings()) timing[t.node] = t;
  EXPECT_TRUE(timing["blur"].fused);
  EXPECT_TRUE(timing["vignette"].fused);
  EXPECT_EQ(evaluator.run_counts().count("blur"), 0u) << "the blur ran a pass of its own";
  EXPECT_EQ(evaluator.run_counts().at("tint"), 1) << "the chain's one pass";
  // A second frame with nothing changed is cached whole.
  auto again = evaluator.evaluate(read.graph, eval);
  ASSERT_TRUE(again.ok()) << again.message();
  EXPECT_EQ(evaluator.run_counts().at("tint"), 1);
  // A change to the blur reaches the output through the fused pass.
  Graph sharper = read.graph;
  sharper.nodes.at("blur").params["sigma"] = 1.0;
  auto changed = evaluator.evaluate(sharper, eval);
  ASSERT_TRUE(changed.ok()) << changed.message();
  EXPECT_EQ(evaluator.run_counts().at("tint"), 2);
  auto first = evaluator.read_back(*out);
  auto second = evaluator.read_back(*changed);
  ASSERT_TRUE(first.ok() && second.ok());
  EXPECT_GT(max_abs_diff(*first, *second), 1e-3);
}

// edge is pointwise in its image and reads its detection source around the pixel: the host binds
// the source for the fused function. As wobble's epilogue (the flagship's order) and inside a
// plain fused chain, fused equals unfused within 1e-6 in float.
const char* kWobbleEdge = R"({
  "aquarelle": 1,
  "nodes": {
    "input": {"type": "image_input", "params": {"name": "image"}},
    "cells": {"type": "noise", "params": {"type": "worley", "scale": 8, "seed": 3}},
    "wobble": {"type": "wobble", "params": {"strength": 6.0}, "inputs": {"image": "input.image"}},
    "edge": {"type": "edge", "params": {"threshold": 0.05, "softness": 0.2, "factor": 0.5},
             "inputs": {"image": "wobble.image", "source": "cells.image"}},
    "tint": {"type": "tint", "params": {"amount": 0.1}, "inputs": {"image": "input.image"}},
    "edge2": {"type": "edge", "params": {"kernel": "sobel", "factor": 0.3},
              "inputs": {"image": "tint.image", "source": "cells.image"}},
    "vignette": {"type": "vignette", "inputs": {"image": "edge2.image"}},
    "sum": {"type": "edge", "params": {"factor": 1.0},
            "inputs": {"image": "edge.image", "source": "vignette.image"}}
  },
  "output": "sum.image"
})";

TEST(EpilogueFusion, EdgeRunsInsideTheWobbleAndInsideAFusedChain) {
  const Plan plan = plan_of(kWobbleEdge);
  const PlannedPass* edge = plan.pass_of("edge");
  ASSERT_NE(edge, nullptr);
  EXPECT_TRUE(edge->epilogue);
  // `sum` (an edge reading edge.image) joins the chain too.
  EXPECT_EQ(edge->chain, (std::vector<std::string>{"wobble", "edge", "sum"}));
  const PlannedPass* vignette = plan.pass_of("vignette");
  ASSERT_NE(vignette, nullptr);
  EXPECT_EQ(vignette->chain, (std::vector<std::string>{"tint", "edge2", "vignette"}));
  for (const char* output : {"edge.image", "vignette.image"}) {
    RenderOptions fused = options(true);
    fused.precision = "float";
    fused.output = output;
    RenderOptions unfused = options(false);
    unfused.precision = "float";
    unfused.output = output;
    auto a = render_graph(kWobbleEdge, fused, input_images());
    auto b = render_graph(kWobbleEdge, unfused, input_images());
    ASSERT_TRUE(a.ok()) << a.message();
    ASSERT_TRUE(b.ok()) << b.message();
    EXPECT_LE(max_abs_diff(*a, *b), 1e-6) << output;
  }
}

// The flagship's order: pigment_apply (its density bound by the host) joins edge in the wobble's
// draw; fused equals unfused within 1e-6 in float, and the canvas runs as a node of its own.
TEST(EpilogueFusion, PigmentApplyJoinsEdgeInsideTheWobble) {
  const std::string graph = wobble_edge_pigment_graph(
      {{"turbulence_weight", 0.8}}, "tint", {{"type", "tint"}, {"params", {{"amount", 0.1}}}});
  const Plan plan = plan_of(graph);
  const PlannedPass* pass = plan.pass_of("tint");
  ASSERT_NE(pass, nullptr);
  EXPECT_TRUE(pass->epilogue);
  EXPECT_EQ(pass->chain, (std::vector<std::string>{"wobble", "edge", "pigment", "tint"}));
  EXPECT_FALSE(plan.find("canvas")->deferred);
  RenderOptions fused = options(true);
  fused.precision = "float";
  RenderOptions unfused = options(false);
  unfused.precision = "float";
  auto a = render_graph(graph, fused, input_images());
  auto b = render_graph(graph, unfused, input_images());
  ASSERT_TRUE(a.ok()) << a.message();
  ASSERT_TRUE(b.ok()) << b.message();
  EXPECT_LE(max_abs_diff(*a, *b), 1e-6);
  auto plain = render_graph(
      graph,
      [&] {
        RenderOptions o = unfused;
        o.output = "edge.image";
        return o;
      }(),
      input_images());
  ASSERT_TRUE(plain.ok()) << plain.message();
  EXPECT_GT(max_abs_diff(*b, *plain), 1e-3) << "the pigment did something";
}

// Without `source`, edge detects on its own image's neighbourhood: not pointwise, not fused.
TEST(EpilogueFusion, EdgeWithoutASourceRunsOnItsOwn) {
  const Plan plan = plan_of(R"({
    "aquarelle": 1,
    "nodes": {
      "input": {"type": "image_input", "params": {"name": "image"}},
      "wobble": {"type": "wobble", "inputs": {"image": "input.image"}},
      "edge": {"type": "edge", "inputs": {"image": "wobble.image"}},
      "tint": {"type": "tint", "inputs": {"image": "edge.image"}}
    },
    "output": "tint.image"
  })");
  EXPECT_EQ(plan.pass_of("edge")->chain, std::vector<std::string>{"edge"});
  EXPECT_FALSE(plan.find("wobble")->deferred);
}

// The flag promises shaders that write output 0 through aq_epilogue: a pointwise node (fused by
// its function instead) or a node whose output 0 is no image is refused, naming the flag.
TEST(EpilogueFusion, OnlyANonPointwiseImageProducerMayTakeAnEpilogue) {
  static const aq_port_desc image[] = {{"image", AQ_PORT_IMAGE, 0, "i"}};
  static const aq_port_desc scene[] = {{"scene", AQ_PORT_SCENE, 0, "s"}};
  static const aq_pointwise_desc function = {
      sizeof(aq_pointwise_desc), "f.glsl", "vec4 AQ_APPLY(vec4 c, vec2 p, vec2 s) { return c; }",
      [](void*, aq_process_ctx*, uint32_t, const char*) { return int{AQ_OK}; }, 0};
  auto [accepted, none] = describe_node(image, image, AQ_NODE_EPILOGUE);
  ASSERT_FALSE(accepted.name.empty()) << none;
  EXPECT_TRUE(accepted.takes_epilogue());
  for (auto [type, why] :
       {describe_node(image, image, AQ_NODE_EPILOGUE | AQ_NODE_POINTWISE, &function),
        describe_node(image, scene, AQ_NODE_EPILOGUE)}) {
    EXPECT_TRUE(type.name.empty());
    EXPECT_NE(why.find("AQ_NODE_EPILOGUE"), std::string::npos) << why;
  }
}

}  // namespace
}  // namespace aq::test
