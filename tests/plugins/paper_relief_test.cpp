// Headless tests of the `paper_relief` node against reference/paper_relief.h, with the
// `paper` node's own height field and with random heights; flat paper and relief 0 exact; paper
// colour through a mask; 1x1; NaN stays put.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <map>
#include <string>

#include "aquarelle/reference/paper_relief.h"
#include "support/harness.h"

namespace {

using aq::ImageF;
using aq::reference::PaperReliefParams;

aq::Result<ImageF> run(const ImageF& image, const ImageF& paper, const ImageF* mask,
                       const PaperReliefParams& p, const char* precision = "float") {
  std::map<std::string, ImageF> inputs{{"image", image}, {"paper", paper}};
  if (mask) inputs["mask"] = *mask;
  aq::test::RenderOptions options;
  options.precision = precision;
  return aq::test::run_node(
      "paper_relief", inputs,
      {{"light", {p.light[0], p.light[1], p.light[2]}},
       {"bump", p.bump},
       {"relief", p.relief},
       {"paper_color", {p.paper_color[0], p.paper_color[1], p.paper_color[2]}},
       {"show", p.show}},
      options);
}

TEST(PaperRelief, MatchesReference) {
  const ImageF image = aq::test::random_image(48, 36, 21);
  const ImageF mask = aq::test::random_image(24, 18, 22, -0.2f, 1.2f);
  aq::test::RenderOptions paper_options;
  paper_options.width = 48;
  paper_options.height = 36;
  auto paper = aq::test::run_node("paper", {}, {{"grain_scale", 12}}, paper_options);
  ASSERT_TRUE(paper.ok()) << paper.message();
  const ImageF random_paper = aq::test::random_image(30, 20, 23);
  const ImageF* heights[] = {&*paper, &random_paper};
  for (const ImageF* height : heights) {
    for (const ImageF* m : {static_cast<const ImageF*>(nullptr), &mask}) {
      PaperReliefParams p;
      p.bump = 6.0;
      const ImageF expected = aq::reference::paper_relief(image, *height, m, p);
      auto got = run(image, *height, m, p);
      ASSERT_TRUE(got.ok()) << got.message();
      const double error = aq::test::max_abs_diff(*got, expected);
      EXPECT_LE(error, 5e-6);
      auto half = run(image, *height, m, p, "half");
      ASSERT_TRUE(half.ok()) << half.message();
      EXPECT_LE(aq::test::max_abs_diff(*half, expected), 2e-3);
      std::printf("[paper_relief] float max abs %.3g\n", error);
    }
  }
  EXPECT_GT(aq::test::max_abs_diff(*run(image, *paper, nullptr, {}), image), 0.01);  // relief shows
}

// Inputs of other sizes are read at x · their width / the image's width (integer division, as
// the reference does). The shader no longer divides integers (aquarelle/integer_division.glsl: a
// float estimate and a correction); at these widths the products pass 2^24, where the estimate
// alone is one off for some pixels and the correction must make it exact.
TEST(PaperRelief, WideInputsOfOtherSizesAreReadAtTheExactTexel) {
  const ImageF image = aq::test::random_image(16001, 1, 31);
  const ImageF paper = aq::test::random_image(16383, 3, 32);
  const ImageF mask = aq::test::random_image(12289, 1, 33, 0.0f, 1.0f);
  PaperReliefParams p;
  p.bump = 6.0;
  const ImageF expected = aq::reference::paper_relief(image, paper, &mask, p);
  auto got = run(image, paper, &mask, p);
  ASSERT_TRUE(got.ok()) << got.message();
  EXPECT_LE(aq::test::max_abs_diff(*got, expected), 5e-6);
}

TEST(PaperRelief, FlatPaperAndZeroReliefAreExact) {
  const ImageF image = aq::test::random_image(33, 17, 24, 0.0f, 2.0f);
  const ImageF flat = aq::test::constant_image(16, 16, 0.5f, 0.5f, 0.5f);
  auto got = run(image, flat, nullptr, {});
  ASSERT_TRUE(got.ok()) << got.message();
  EXPECT_EQ(aq::test::max_abs_diff(*got, image), 0.0);
  PaperReliefParams none;
  none.relief = 0.0;
  auto zero = run(image, aq::test::random_image(16, 16, 25), nullptr, none);
  ASSERT_TRUE(zero.ok()) << zero.message();
  EXPECT_EQ(aq::test::max_abs_diff(*zero, image), 0.0);
}

TEST(PaperRelief, PaperColourShowsThroughTheMask) {
  const ImageF image = aq::test::constant_image(8, 8, 0.1f, 0.2f, 0.3f);
  const ImageF flat = aq::test::constant_image(8, 8, 0.5f, 0.5f, 0.5f);
  const ImageF full = aq::test::constant_image(8, 8, 1.0f, 1.0f, 1.0f);
  auto got = run(image, flat, &full, {});
  ASSERT_TRUE(got.ok()) << got.message();
  EXPECT_NEAR(got->at(3, 3, 0), 0.96f, 1e-6);
  EXPECT_NEAR(got->at(3, 3, 2), 0.85f, 1e-6);
}

TEST(PaperRelief, OnePixelAndNaN) {
  const ImageF one = aq::test::constant_image(1, 1, 0.2f, 0.4f, 0.6f);
  auto got = run(one, aq::test::random_image(1, 1, 3), nullptr, {});
  ASSERT_TRUE(got.ok()) << got.message();
  EXPECT_EQ(aq::test::max_abs_diff(*got, one), 0.0);  // one texel: no slope
  ImageF paper = aq::test::random_image(16, 16, 26);
  paper.at(5, 5, 0) = std::numeric_limits<float>::quiet_NaN();
  ImageF image = aq::test::random_image(16, 16, 27);
  image.at(9, 9, 2) = std::numeric_limits<float>::quiet_NaN();
  auto nan = run(image, paper, nullptr, {});
  ASSERT_TRUE(nan.ok()) << nan.message();
  int non_finite = 0;
  for (int y = 0; y < 16; ++y)
    for (int x = 0; x < 16; ++x)
      for (int c = 0; c < 4; ++c) non_finite += std::isfinite(nan->at(x, y, c)) ? 0 : 1;
  EXPECT_EQ(non_finite, 1);
}

// The node is pointwise (issue 35's speed): the host runs it as the epilogue of the tremor's pass
// and fused with the tint after it. That must be the function its own pass computes: the chain
// rendered fused and node by node agrees (float precision, so no store rounds between them).
TEST(PaperRelief, FusedIntoTheTremorAndTintItIsTheSameFunction) {
  const std::string graph = R"({
  "aquarelle": 1,
  "nodes": {
    "input": {"type": "image_input", "params": {"name": "image"}},
    "paper": {"type": "image_input", "params": {"name": "paper"}},
    "mask": {"type": "image_input", "params": {"name": "mask"}},
    "wobble": {"type": "tremor", "params": {"amplitude": 2.0, "wavelength": 8.0},
               "inputs": {"image": "input.image"}},
    "relief": {"type": "paper_relief", "params": {"bump": 3.0, "relief": 0.8, "show": 0.6},
               "inputs": {"image": "wobble.image", "paper": "paper.image", "mask": "mask.image"}},
    "tint": {"type": "tint", "params": {"amount": 0.2}, "inputs": {"image": "relief.image"}}
  },
  "output": "tint.image"
})";
  const std::map<std::string, ImageF> images{{"image", aq::test::random_image(80, 48, 3)},
                                             {"paper", aq::test::random_image(80, 48, 4)},
                                             {"mask", aq::test::random_image(80, 48, 5)}};
  aq::test::RenderOptions fused;
  fused.width = 80;
  fused.height = 48;
  aq::test::RenderOptions apart = fused;
  apart.fuse_pointwise = false;
  auto one_pass = aq::test::render_graph(graph, fused, images);
  auto node_by_node = aq::test::render_graph(graph, apart, images);
  ASSERT_TRUE(one_pass.ok()) << one_pass.message();
  ASSERT_TRUE(node_by_node.ok()) << node_by_node.message();
  EXPECT_LE(aq::test::max_abs_diff(*one_pass, *node_by_node), 1e-5);
  // The relief did something: the paper's relief is visible against the tremor alone.
  EXPECT_GT(aq::test::mean_abs_diff(*one_pass, images.at("image")), 0.01);
}

}  // namespace
