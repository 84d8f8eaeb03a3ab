// Bandwidth by need (plan.h, PlannedNode::eight_bit_outputs): an output whose every reader
// reads it through an AQ_PORT_8BIT_ENOUGH input is stored as RGBA8. The plan tests need no
// GL; the render tests compare the lever on and off (AQUARELLE_FORMATS_BY_NEED=0) against the
// error bound that 8-bit storage of edge's detection source allows.
#include <gtest/gtest.h>

#include <aquarelle/core/graph_io.h>
#include <aquarelle/core/plan.h>

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
  return node != nullptr && !node->eight_bit_outputs.empty() && node->eight_bit_outputs[0];
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
                                 const std::string& precision);

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

Result<ImageF> render_with_lever(const char* graph, bool formats_by_need,
                                 const std::string& precision) {
  if (formats_by_need) {
    unsetenv("AQUARELLE_FORMATS_BY_NEED");
  } else {
    setenv("AQUARELLE_FORMATS_BY_NEED", "0", 1);
  }
  RenderOptions options;
  options.width = 128;
  options.height = 96;
  options.precision = precision;
  auto image = render_graph(graph, options);
  unsetenv("AQUARELLE_FORMATS_BY_NEED");
  return image;
}

}  // namespace
}  // namespace aq::test
