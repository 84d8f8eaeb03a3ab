// Pointwise fusion: chains of pointwise nodes that give their per-pixel function run as one
// pass, and the output's pointwise tail runs inside the proxy upscale. Fused and unfused
// results must agree; a fused node's own output stays viewable.
#include <gtest/gtest.h>

#include <aquarelle/core/evaluator.h>
#include <aquarelle/core/graph_io.h>

#include "support/harness.h"

namespace aq::test {
namespace {

// input -> tint -> vignette -> dim (a second tint): three fusable pointwise nodes in a row.
const char* kChain = R"({
  "aquarelle": 1,
  "nodes": {
    "input": {"type": "image_input", "params": {"name": "image"}},
    "tint": {"type": "tint", "params": {"amount": 0.3, "tint": [0.1, 0.4, 0.2]},
             "inputs": {"image": "input.image"}},
    "vignette": {"type": "vignette", "params": {"radius": 0.2, "strength": 0.8},
                 "inputs": {"image": "tint.image"}},
    "dim": {"type": "tint", "params": {"amount": 0.5, "tint": [0, 0, 0]},
            "inputs": {"image": "vignette.image"}}
  },
  "output": "dim.image"
})";

RenderOptions options(bool fuse, const char* quality = "final") {
  RenderOptions o;
  o.width = 96;
  o.height = 64;
  o.quality = quality;
  o.fuse_pointwise = fuse;
  return o;
}

std::map<std::string, ImageF> input_images(int width = 96, int height = 64) {
  return {{"image", random_image(width, height, 11, -0.5f, 2.0f)}};
}

TEST(Fusion, FusedChainEqualsOneNodeAfterAnother) {
  auto fused = render_graph(kChain, options(true), input_images());
  auto unfused = render_graph(kChain, options(false), input_images());
  ASSERT_TRUE(fused.ok()) << fused.message();
  ASSERT_TRUE(unfused.ok()) << unfused.message();
  EXPECT_LE(max_abs_diff(*fused, *unfused), 1e-6);
  // And the chain did something: the vignette darkens the corners.
  EXPECT_GT(max_abs_diff(*fused, input_images().at("image")), 0.1);
}

TEST(Fusion, TheChainRunsAsOnePassAndReportsTheFusedNodes) {
  auto read = read_graph_text(kChain, registry(), "fusion test");
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
  EXPECT_TRUE(timing["tint"].fused);
  EXPECT_TRUE(timing["vignette"].fused);
  EXPECT_FALSE(timing["dim"].fused);
  EXPECT_EQ(evaluator.run_counts().count("tint"), 0u) << "tint ran a pass of its own";
  EXPECT_EQ(evaluator.run_counts().count("vignette"), 0u);
  EXPECT_EQ(evaluator.run_counts().at("dim"), 1);
}

TEST(Fusion, AFusedNodeCanStillBeViewedOnItsOwn) {
  RenderOptions fused = options(true);
  fused.output = "vignette.image";
  RenderOptions unfused = options(false);
  unfused.output = "vignette.image";
  auto a = render_graph(kChain, fused, input_images());
  auto b = render_graph(kChain, unfused, input_images());
  ASSERT_TRUE(a.ok()) << a.message();
  ASSERT_TRUE(b.ok()) << b.message();
  EXPECT_LE(max_abs_diff(*a, *b), 1e-6);
  auto whole = render_graph(kChain, options(true), input_images());
  EXPECT_GT(max_abs_diff(*a, *whole), 0.05) << "the viewed output is vignette's, not dim's";
}

TEST(Fusion, ANodeWithTwoReadersIsNotFused) {
  // tint feeds both vignette and the output's second input path: it must run on its own.
  const char* branching = R"({
    "aquarelle": 1,
    "nodes": {
      "input": {"type": "image_input", "params": {"name": "image"}},
      "tint": {"type": "tint", "params": {"amount": 0.3}, "inputs": {"image": "input.image"}},
      "vignette": {"type": "vignette", "inputs": {"image": "tint.image"}},
      "pigment": {"type": "pigment", "inputs": {"image": "vignette.image", "paper": "tint.image"}}
    },
    "output": "pigment.image"
  })";
  auto fused = render_graph(branching, options(true), input_images());
  auto unfused = render_graph(branching, options(false), input_images());
  ASSERT_TRUE(fused.ok()) << fused.message();
  ASSERT_TRUE(unfused.ok()) << unfused.message();
  EXPECT_LE(max_abs_diff(*fused, *unfused), 1e-6);
}

// At preview the nodes run at half size; the output's pointwise tail then runs inside the
// upscale, at the graph's size. For an affine colour map with constant coefficients (tint),
// interpolating then mapping equals mapping then interpolating.
TEST(Fusion, TheOutputTailRunsInsideTheProxyUpscale) {
  const char* tail = R"({
    "aquarelle": 1,
    "nodes": {
      "noise": {"type": "noise", "params": {"scale": 4}},
      "tint": {"type": "tint", "params": {"amount": 0.4, "tint": [0.2, 0.5, 0.9]},
               "inputs": {"image": "noise.image"}}
    },
    "output": "tint.image"
  })";
  auto fused = render_graph(tail, options(true, "preview"));
  auto unfused = render_graph(tail, options(false, "preview"));
  ASSERT_TRUE(fused.ok()) << fused.message();
  ASSERT_TRUE(unfused.ok()) << unfused.message();
  ASSERT_EQ(fused->width, 96);
  ASSERT_EQ(fused->height, 64);
  EXPECT_LE(max_abs_diff(*fused, *unfused), 2e-6);
}

// The vignette's darkening is evaluated at the output's pixels in the fused tail, so it is
// closer to the full-size render than darkening at half size and interpolating.
TEST(Fusion, AVignetteTailAtOutputSizeIsCloserToTheFullRender) {
  const char* tail = R"({
    "aquarelle": 1,
    "nodes": {
      "input": {"type": "image_input", "params": {"name": "image"}},
      "vignette": {"type": "vignette", "params": {"radius": 0.1, "strength": 1.0, "softness": 0.3},
                   "inputs": {"image": "input.image"}}
    },
    "output": "vignette.image"
  })";
  std::map<std::string, ImageF> flat = {{"image", constant_image(96, 64, 1, 1, 1)}};
  std::map<std::string, ImageF> flat_half = {{"image", constant_image(48, 32, 1, 1, 1)}};
  auto full = render_graph(tail, options(true, "final"), flat);
  RenderOptions half_options = options(true, "preview");
  auto fused = render_graph(tail, half_options, flat_half);
  half_options.fuse_pointwise = false;
  auto unfused = render_graph(tail, half_options, flat_half);
  ASSERT_TRUE(full.ok() && fused.ok() && unfused.ok());
  EXPECT_LE(max_abs_diff(*fused, *full), 1e-5);
  EXPECT_GT(max_abs_diff(*unfused, *full), 1e-3);
}

}  // namespace
}  // namespace aq::test
