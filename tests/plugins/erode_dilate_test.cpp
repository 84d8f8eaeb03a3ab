// Headless tests of the `erode` and `dilate` nodes against the direct 2D CPU reference
// (reference/morphology.h): every size, footprint and order in both precisions, odd image
// shapes, the size-1 identity and the error for an even size. Properties that relate the two
// (ordering, idempotence, borders, no new colours) live in morphology_test.cpp.
#include <gtest/gtest.h>

#include "aquarelle/reference/morphology.h"
#include "plugins/watercolor_test_images.h"
#include "support/harness.h"

#include <string>
#include <tuple>

namespace {

using aq::ImageF;
using aq::reference::MorphologyFootprint;
using aq::reference::MorphologyOp;
using aq::reference::MorphologyOrder;
using aq::test::watercolor::quantized;

aq::reference::MorphologyParams reference_params(const std::string& node, int size,
                                                 const std::string& footprint,
                                                 const std::string& mode) {
  return {node == "erode" ? MorphologyOp::kErode : MorphologyOp::kDilate, size,
          footprint == "disc" ? MorphologyFootprint::kDisc : MorphologyFootprint::kSquare,
          mode == "luminance" ? MorphologyOrder::kLuminance : MorphologyOrder::kPerChannel};
}

aq::test::RenderOptions options_for(const ImageF& image, const std::string& precision) {
  aq::test::RenderOptions options;
  options.width = image.width;
  options.height = image.height;
  options.precision = precision;
  return options;
}

using ReferenceCase = std::tuple<std::string, int, std::string, std::string, std::string>;
class MorphologyReference : public ::testing::TestWithParam<ReferenceCase> {};

// Inputs on a 1/1024 grid are exact in half precision and min/max only select values, so the
// node must reproduce the reference exactly in both precisions.
TEST_P(MorphologyReference, MatchesDirectDefinitionExactly) {
  const auto& [node, size, footprint, mode, precision] = GetParam();
  const ImageF input = quantized(aq::test::random_image(67, 45, 11));
  auto out = aq::test::run_node(node, {{"image", input}},
                                {{"size", size}, {"footprint", footprint}, {"mode", mode}},
                                options_for(input, precision));
  ASSERT_TRUE(out.ok()) << out.message();
  const ImageF expected =
      aq::reference::morphology(input, reference_params(node, size, footprint, mode));
  EXPECT_EQ(aq::test::max_abs_diff(*out, expected), 0.0);
}

INSTANTIATE_TEST_SUITE_P(Sweep, MorphologyReference,
                         ::testing::Combine(::testing::Values("erode", "dilate"),
                                            ::testing::Values(3, 5, 7, 9),
                                            ::testing::Values("square", "disc"),
                                            ::testing::Values("channel", "luminance"),
                                            ::testing::Values("float", "half")));

class Morphology : public ::testing::TestWithParam<std::string> {
 protected:
  const std::string& node() const { return GetParam(); }
};

// Unquantised input: float keeps it exactly; half stores each selected value rounded once.
TEST_P(Morphology, ArbitraryInputWithinStoragePrecision) {
  const ImageF input = aq::test::random_image(64, 64, 3);
  const ImageF expected =
      aq::reference::morphology(input, reference_params(node(), 5, "square", "channel"));
  auto exact =
      aq::test::run_node(node(), {{"image", input}}, {{"size", 5}}, options_for(input, "float"));
  ASSERT_TRUE(exact.ok()) << exact.message();
  EXPECT_LE(aq::test::max_abs_diff(*exact, expected), 1e-7);
  auto half =
      aq::test::run_node(node(), {{"image", input}}, {{"size", 5}}, options_for(input, "half"));
  ASSERT_TRUE(half.ok()) << half.message();
  EXPECT_LE(aq::test::max_abs_diff(*half, expected), 1.0 / 2048.0);  // half ulp below 1 is 2^-11
  EXPECT_GE(aq::test::psnr(*half, expected), 70.0);
}

TEST_P(Morphology, SizeOneIsIdentity) {
  const ImageF input = aq::test::random_image(64, 64, 5);
  for (const char* mode : {"channel", "luminance"}) {
    auto out = aq::test::run_node(node(), {{"image", input}}, {{"size", 1}, {"mode", mode}},
                                  options_for(input, "float"));
    ASSERT_TRUE(out.ok()) << out.message();
    EXPECT_EQ(aq::test::max_abs_diff(*out, input), 0.0) << mode;
  }
}

TEST_P(Morphology, OddImageShapes) {
  for (const auto& [w, h] : {std::pair{1, 1}, std::pair{1, 9}, std::pair{13, 1}, std::pair{3, 2}}) {
    const ImageF input = quantized(aq::test::random_image(w, h, 17));
    for (const char* footprint : {"square", "disc"}) {
      auto out =
          aq::test::run_node(node(), {{"image", input}}, {{"size", 9}, {"footprint", footprint}},
                             options_for(input, "float"));
      ASSERT_TRUE(out.ok()) << out.message();
      const ImageF expected =
          aq::reference::morphology(input, reference_params(node(), 9, footprint, "channel"));
      EXPECT_EQ(aq::test::max_abs_diff(*out, expected), 0.0) << w << "x" << h << " " << footprint;
    }
  }
}

TEST_P(Morphology, EvenSizeIsRefusedWithAFix) {
  const ImageF input = aq::test::random_image(16, 16, 1);
  auto out =
      aq::test::run_node(node(), {{"image", input}}, {{"size", 4}}, options_for(input, "float"));
  ASSERT_FALSE(out.ok());
  EXPECT_NE(out.message().find("odd"), std::string::npos) << out.message();
}

INSTANTIATE_TEST_SUITE_P(Nodes, Morphology, ::testing::Values("erode", "dilate"));

}  // namespace
