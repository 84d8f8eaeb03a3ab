// Bandwidth by need (plan.h, PlannedNode::eight_bit_outputs): an output whose every reader
// reads it through an AQ_PORT_8BIT_ENOUGH input is stored as RGBA8. The plan tests need no
// GL; the render tests compare the lever on and off (AQUARELLE_FORMATS_BY_NEED=0) against the
// error bound that 8-bit storage of edge's detection source allows.
#include <gtest/gtest.h>

#include <aquarelle/core/graph_io.h>
#include <aquarelle/core/plan.h>
#include <aquarelle/core/registry.h>

#include <cstdio>
#include <cstdlib>

#include "support/harness.h"

namespace aq::test {
namespace {

// Worley cells (sharp creases: strong edge responses) as edge's detection source, a smooth
// noise as the colour it darkens.
const char* kEdgeGraph = R"({
  "aquarelle": 1,
  "settings": {"width": 128, "height": 96},
  "nodes": {
    "cells": {"type": "noise", "params": {"type": "worley", "scale": 10, "seed": 4}},
    "colour": {"type": "noise", "params": {"scale": 3, "seed": 9}},
    "edge": {"type": "edge", "params": {"threshold": 0.05, "softness": 0.2},
             "inputs": {"image": "colour.image", "source": "cells.image"}}
  },
  "output": "edge.image"
})";

// The same source read by edge and by a tint, which wants its full precision.
const char* kSharedSource = R"({
  "aquarelle": 1,
  "settings": {"width": 64, "height": 64},
  "nodes": {
    "cells": {"type": "noise", "params": {"type": "worley", "scale": 10}},
    "colour": {"type": "noise", "params": {"scale": 3}},
    "edge": {"type": "edge", "inputs": {"image": "colour.image", "source": "cells.image"}},
    "tinted": {"type": "tint", "inputs": {"image": "cells.image"}},
    "mix": {"type": "edge", "inputs": {"image": "tinted.image", "source": "edge.image"}}
  },
  "output": "mix.image"
})";

Plan plan_of(const char* text, bool formats_by_need = true,
             const std::optional<PortRef>& output = std::nullopt) {
  auto read = read_graph_text(text, registry(), "formats test");
  EXPECT_TRUE(read.ok());
  PlanOptions options;
  options.formats_by_need = formats_by_need;
  auto plan = compile_plan(read.graph, registry(), options, output);
  EXPECT_TRUE(plan.ok()) << plan.message();
  return plan.ok() ? *plan : Plan{};
}

bool stored_in_8_bits(const Plan& plan, const std::string& id) {
  const PlannedNode* node = plan.find(id);
  return node != nullptr && !node->stored_formats.empty() &&
         node->stored_formats[0] == AQ_FORMAT_RGBA8;
}

TEST(FormatsByNeed, AnOutputReadOnlyForEdgeDetectionIsStoredIn8Bits) {
  const Plan plan = plan_of(kEdgeGraph);
  EXPECT_TRUE(stored_in_8_bits(plan, "cells"));
  EXPECT_FALSE(stored_in_8_bits(plan, "colour")) << "edge's image input keeps full precision";
  EXPECT_FALSE(stored_in_8_bits(plan, "edge")) << "the requested output keeps its format";
  EXPECT_NE(format_plan(plan).find("[RGBA8: image]"), std::string::npos) << format_plan(plan);
}

TEST(FormatsByNeed, OneReaderThatNeedsPrecisionKeepsTheFormat) {
  const Plan plan = plan_of(kSharedSource);
  EXPECT_FALSE(stored_in_8_bits(plan, "cells")) << "tint reads it too";
  EXPECT_TRUE(stored_in_8_bits(plan, "edge")) << "read only as mix's detection source";
}

TEST(FormatsByNeed, ViewingTheOutputOrTurningTheLeverOffKeepsTheFormat) {
  EXPECT_FALSE(stored_in_8_bits(plan_of(kEdgeGraph, true, PortRef{"cells", "image"}), "cells"));
  EXPECT_FALSE(stored_in_8_bits(plan_of(kEdgeGraph, false), "cells"));
}

Result<ImageF> render_with_lever(const char* graph, bool formats_by_need,
                                 const std::string& precision, const std::string& output = "");

// The flag says how a node reads an image: a plugin declaring it on an output or on a scene
// input is refused with a message naming the port.
TEST(FormatsByNeed, OnlyImageInputsMayDeclareIt) {
  const aq_port_desc scene_input[] = {{"scene", AQ_PORT_SCENE, AQ_PORT_8BIT_ENOUGH, "s"}};
  const aq_port_desc image_input[] = {{"mask", AQ_PORT_IMAGE, AQ_PORT_8BIT_ENOUGH, "m"}};
  const aq_port_desc narrow_output[] = {{"image", AQ_PORT_IMAGE, AQ_PORT_8BIT_ENOUGH, "i"}};
  const aq_port_desc plain_output[] = {{"image", AQ_PORT_IMAGE, 0, "i"}};
  auto [accepted, none] = describe_node(image_input, plain_output);
  ASSERT_FALSE(accepted.name.empty()) << none;
  EXPECT_TRUE(accepted.inputs[0].eight_bit_enough);
  auto [on_scene, why_scene] = describe_node(scene_input, plain_output);
  EXPECT_TRUE(on_scene.name.empty());
  EXPECT_NE(why_scene.find("input 'scene' is AQ_PORT_8BIT_ENOUGH"), std::string::npos) << why_scene;
  auto [on_output, why_output] = describe_node(image_input, narrow_output);
  EXPECT_TRUE(on_output.name.empty());
  EXPECT_NE(why_output.find("output 'image' is AQ_PORT_8BIT_ENOUGH"), std::string::npos)
      << why_output;
}

// AQ_PORT_HDR8 (the encoded 8-bit HDR format, tests/core/hdr8_test.cpp) is about the image a
// port holds, on inputs and outputs alike: only scene ports are refused.
TEST(FormatsByNeed, OnlyImagePortsMayHandleTheEncodedHdrFormat) {
  const aq_port_desc scene_input[] = {{"scene", AQ_PORT_SCENE, AQ_PORT_HDR8, "s"}};
  const aq_port_desc image_input[] = {{"image", AQ_PORT_IMAGE, AQ_PORT_HDR8, "i"}};
  const aq_port_desc image_output[] = {{"image", AQ_PORT_IMAGE, AQ_PORT_HDR8, "i"}};
  auto [refused, why] = describe_node(scene_input, image_output);
  EXPECT_TRUE(refused.name.empty());
  EXPECT_NE(why.find("input 'scene' is AQ_PORT_HDR8"), std::string::npos) << why;
  auto [accepted, none] = describe_node(image_input, image_output);
  ASSERT_FALSE(accepted.name.empty()) << none;
  EXPECT_TRUE(accepted.inputs[0].hdr8);
  EXPECT_TRUE(accepted.outputs[0].hdr8);
}

// Storing the source in 8 bits moves each of the Laplacian's 9 texels by at most 1/510; with
// weights of absolute sum 16 the response moves by at most 16/510, the smoothstep's slope is at
// most 1.5 / softness, and the colour (noise in [0, 1]) is scaled by at most (1 - factor) of
// that: the stated bound.
TEST(FormatsByNeed, EdgeOnAn8BitSourceStaysWithinTheQuantisationBound) {
  const double factor = 0.7, softness = 0.2;
  const double bound = (1.0 - factor) * (1.5 / softness) * (16.0 / 510.0);  // 0.0706
  for (const char* precision : {"float", "half"}) {
    auto narrow = render_with_lever(kEdgeGraph, true, precision);
    auto full = render_with_lever(kEdgeGraph, false, precision);
    ASSERT_TRUE(narrow.ok()) << narrow.message();
    ASSERT_TRUE(full.ok()) << full.message();
    const double max_error = max_abs_diff(*narrow, *full);
    const double mean_error = mean_abs_diff(*narrow, *full);
    EXPECT_GT(max_error, 0.0) << precision << ": the source was not stored in 8 bits";
    EXPECT_LE(max_error, bound) << precision;
    // This source is a worst case (Worley creases everywhere, threshold 0.05: most pixels on
    // the ramp); measured mean 1.8e-3, 47.8 dB in both precisions. On graphs/underwater.json
    // the pipeline's PSNR against the reference is what docs/performance.md reports.
    EXPECT_LE(mean_error, 2.5e-3) << precision;
    EXPECT_GE(psnr(*narrow, *full), 45.0) << precision;
    std::printf("%s: max %.4g (bound %.4g), mean %.3g\n", precision, max_error, bound, mean_error);
  }
}

// The paper feeds wobble (its gradient, and its height for the size) and pigment (a density):
// both paper inputs are content with 8 bits, the gradient is not read that way.
const char* kPaperGraph = R"({
  "aquarelle": 1,
  "settings": {"width": 128, "height": 96},
  "nodes": {
    "colour": {"type": "noise", "params": {"scale": 3, "seed": 2}},
    "paper": {"type": "paper", "params": {"seed": 3}},
    "wobble": {"type": "wobble", "params": {"strength": 8.0},
               "inputs": {"image": "colour.image", "paper": "paper.image",
                          "gradient": "paper.gradient"}},
    "pigment": {"type": "pigment",
                "params": {"turbulence_weight": 0.0, "grain_weight": 0.0, "paper_weight": 0.2},
                "inputs": {"image": "wobble.image", "paper": "paper.image"}}
  },
  "output": "pigment.image"
})";

TEST(FormatsByNeed, ThePaperIsStoredIn8BitsAndItsGradientIsNot) {
  const Plan plan = plan_of(kPaperGraph);
  const PlannedNode* paper = plan.find("paper");
  ASSERT_NE(paper, nullptr);
  ASSERT_EQ(paper->stored_formats.size(), 2u);
  EXPECT_EQ(paper->stored_formats[0], uint32_t{AQ_FORMAT_RGBA8})
      << "image: read by wobble.paper and pigment.paper";
  EXPECT_EQ(paper->stored_formats[1], 0u) << "gradient: wobble reads it at full precision";
}

Result<ImageF> render_with_lever(const char* graph, bool formats_by_need,
                                 const std::string& precision, const std::string& output) {
  if (formats_by_need) {
    unsetenv("AQUARELLE_FORMATS_BY_NEED");
  } else {
    setenv("AQUARELLE_FORMATS_BY_NEED", "0", 1);
  }
  RenderOptions options;
  options.width = 128;
  options.height = 96;
  options.precision = precision;
  options.output = output;
  auto image = render_graph(graph, options);
  unsetenv("AQUARELLE_FORMATS_BY_NEED");
  return image;
}

// pigment's last density stage is C' = C(1 - (1 - C)(d - 1)), d = 1 + weight n: a density error
// e moves C' by at most weight C(1 - C) e <= weight e / 4. An 8-bit texel is within 1/510 and
// llvmpipe's 8-bit bilinear weights add at most another 1/510 between neighbours, so
// e <= 2/510; wobble's gradient is differenced at full precision and does not move. Half
// precision adds its own output rounding (< 1e-3 below 1) on either side.
TEST(FormatsByNeed, PaperIn8BitsForPigmentAndWobble) {
  const double paper_weight = 0.2;
  const double bound = paper_weight / 4.0 * (2.0 / 510.0);  // 2.0e-4
  for (const char* precision : {"float", "half"}) {
    auto narrow = render_with_lever(kPaperGraph, true, precision);
    auto full = render_with_lever(kPaperGraph, false, precision);
    ASSERT_TRUE(narrow.ok()) << narrow.message();
    ASSERT_TRUE(full.ok()) << full.message();
    const double slack = std::string(precision) == "half" ? 1e-3 : 1e-6;
    EXPECT_GT(max_abs_diff(*narrow, *full), 0.0) << precision << ": the paper was not narrowed";
    EXPECT_LE(max_abs_diff(*narrow, *full), bound + slack) << precision;
    // wobble reads the gradient, which paper differences from its full-precision height: the
    // same with the paper in 8 bits (wobble.paper is then its only reader, still narrowed).
    auto wobbled = render_with_lever(kPaperGraph, true, precision, "wobble.image");
    auto wobbled_full = render_with_lever(kPaperGraph, false, precision, "wobble.image");
    ASSERT_TRUE(wobbled.ok() && wobbled_full.ok());
    EXPECT_EQ(max_abs_diff(*wobbled, *wobbled_full), 0.0) << precision;
  }
}

}  // namespace
}  // namespace aq::test
