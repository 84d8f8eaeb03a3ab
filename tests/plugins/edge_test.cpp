// Headless tests of the `edge` node against the double-precision reference
// (reference/edge.h, which goes through HSV): a constant image changes nothing, factor 1
// is the identity, both kernels match the reference over a sweep of factor, threshold and
// softness in both precisions, the darkening ramps smoothly, the `source` input decides where
// edges are (seed §7.3), and NaN in the source does not spread.
#include <gtest/gtest.h>

#include "aquarelle/reference/edge.h"
#include "support/harness.h"

#include <cmath>
#include <limits>
#include <map>
#include <string>
#include <tuple>

namespace {

using aq::ImageF;

// Blocks of 8 pixels whose red steps by 0.05 (Laplacian response 0.15 beside a step, inside the
// default ramp [0.1, 0.3]), a smooth green wave and a coarse blue staircase: edges of every
// strength, like a cel-shaded image.
ImageF blocky_image(int width, int height) {
  ImageF image(width, height, 4, 1.0f);
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) {
      image.at(x, y, 0) = 0.3f + 0.05f * static_cast<float>((x / 8 + y / 8) % 5);
      image.at(x, y, 1) = 0.5f + 0.4f * static_cast<float>(std::sin(0.15 * x + 0.1 * y));
      image.at(x, y, 2) = 0.2f + 0.1f * static_cast<float>((x / 16) % 3);
    }
  }
  return image;
}

aq::test::RenderOptions options_for(const ImageF& image, const std::string& precision) {
  aq::test::RenderOptions options;
  options.width = image.width;
  options.height = image.height;
  options.precision = precision;
  return options;
}

aq::reference::EdgeKernel kernel_of(const std::string& name) {
  return name == "sobel" ? aq::reference::EdgeKernel::kSobel
                         : aq::reference::EdgeKernel::kLaplacian;
}

TEST(Edge, ConstantImageChangesNothing) {
  const ImageF input = aq::test::constant_image(40, 30, 0.25f, 0.5f, 0.75f, 1.0f);
  for (const char* kernel : {"laplacian", "sobel"}) {
    for (double threshold : {0.0, 0.1}) {
      for (const char* precision : {"float", "half"}) {
        auto out = aq::test::run_node("edge", {{"image", input}},
                                      {{"kernel", kernel}, {"threshold", threshold}},
                                      options_for(input, precision));
        ASSERT_TRUE(out.ok()) << out.message();
        EXPECT_EQ(aq::test::max_abs_diff(*out, input), 0.0)
            << kernel << " threshold " << threshold << " " << precision;
      }
    }
  }
}

TEST(Edge, FactorOneIsIdentity) {
  const ImageF input = aq::test::checker_image(32, 32, 4);
  auto out = aq::test::run_node("edge", {{"image", input}}, {{"factor", 1.0}},
                                options_for(input, "float"));
  ASSERT_TRUE(out.ok()) << out.message();
  EXPECT_EQ(aq::test::max_abs_diff(*out, input), 0.0);
}

using ReferenceCase = std::tuple<std::string, double, std::string>;
class EdgeReference : public ::testing::TestWithParam<ReferenceCase> {};

// Measured on llvmpipe: float ≈ 1e-7 (the shader scales RGB directly, the reference goes through
// HSV), half ≈ 4.9e-4 (RGBA16F output rounding).
TEST_P(EdgeReference, MatchesReference) {
  const auto& [kernel, factor, precision] = GetParam();
  const ImageF input = blocky_image(64, 64);
  auto out =
      aq::test::run_node("edge", {{"image", input}}, {{"kernel", kernel}, {"factor", factor}},
                         options_for(input, precision));
  ASSERT_TRUE(out.ok()) << out.message();
  aq::reference::EdgeParams params;
  params.kernel = kernel_of(kernel);
  params.factor = factor;
  const ImageF expected = aq::reference::edge_darkening(input, nullptr, params);
  const double error = aq::test::max_abs_diff(*out, expected);
  const double psnr = aq::test::psnr(*out, expected);
  EXPECT_LE(error, precision == "float" ? 1e-5 : 1e-3);
  EXPECT_GE(psnr, precision == "float" ? 100.0 : 70.0);
  RecordProperty("max_abs_error", std::to_string(error));
  RecordProperty("psnr_db", std::to_string(psnr));
  // Something was darkened, unless the factor is 1.
  EXPECT_GT(aq::test::max_abs_diff(expected, input), 0.1);
}

INSTANTIATE_TEST_SUITE_P(Sweep, EdgeReference,
                         ::testing::Combine(::testing::Values("laplacian", "sobel"),
                                            ::testing::Values(0.0, 0.35, 0.7),
                                            ::testing::Values("float", "half")));

TEST(Edge, ThresholdAndSoftnessSweep) {
  const ImageF input = blocky_image(48, 48);
  for (double threshold : {0.0, 0.05, 0.5, 2.0}) {
    for (double softness : {0.01, 0.2, 1.0}) {
      for (const char* kernel : {"laplacian", "sobel"}) {
        auto out = aq::test::run_node(
            "edge", {{"image", input}},
            {{"kernel", kernel}, {"threshold", threshold}, {"softness", softness}},
            options_for(input, "float"));
        ASSERT_TRUE(out.ok()) << out.message();
        aq::reference::EdgeParams params;
        params.kernel = kernel_of(kernel);
        params.threshold = threshold;
        params.softness = softness;
        const ImageF expected = aq::reference::edge_darkening(input, nullptr, params);
        // A steep ramp amplifies the float rounding of the response by its slope, 1.5 / softness
        // (measured: 3.3e-5 at softness 0.01).
        EXPECT_LE(aq::test::max_abs_diff(*out, expected), 1e-5 + 1e-6 / softness)
            << kernel << " threshold " << threshold << " softness " << softness;
      }
    }
  }
}

// The default ramp is smooth: beside the 0.05 red steps the response (0.15) lies inside
// [0.1, 0.3], so some pixels are darkened by a factor strictly between 0.7 and 1.
TEST(Edge, DarkeningIsSmoothNotAHardStep) {
  const ImageF input = blocky_image(64, 64);
  auto out = aq::test::run_node("edge", {{"image", input}}, {}, options_for(input, "float"));
  ASSERT_TRUE(out.ok()) << out.message();
  int partial = 0;
  for (int y = 0; y < input.height; ++y) {
    for (int x = 0; x < input.width; ++x) {
      const double ratio = out->at(x, y, 0) / input.at(x, y, 0);
      partial += ratio > 0.71 && ratio < 0.99;
    }
  }
  EXPECT_GT(partial, 20);
}

// Seed §7.3: with `source` connected, only the source's edges darken the image.
TEST(Edge, SourceDecidesWhereEdgesAre) {
  const ImageF busy = aq::test::checker_image(64, 64, 4);
  const ImageF plain = aq::test::constant_image(64, 64, 0.6f, 0.5f, 0.4f, 1.0f);
  auto untouched = aq::test::run_node("edge", {{"image", busy}, {"source", plain}}, {},
                                      options_for(busy, "float"));
  ASSERT_TRUE(untouched.ok()) << untouched.message();
  EXPECT_EQ(aq::test::max_abs_diff(*untouched, busy), 0.0);

  const ImageF source = blocky_image(32, 32);  // half the size: stretched over the image
  auto darkened = aq::test::run_node("edge", {{"image", plain}, {"source", source}}, {},
                                     options_for(plain, "float"));
  ASSERT_TRUE(darkened.ok()) << darkened.message();
  const ImageF expected = aq::reference::edge_darkening(plain, &source, {});
  EXPECT_LE(aq::test::max_abs_diff(*darkened, expected), 1e-5);
  EXPECT_GT(aq::test::max_abs_diff(*darkened, plain), 0.1);
}

TEST(Edge, NanInSourceDoesNotSpread) {
  const ImageF input = blocky_image(32, 32);
  ImageF source = input;
  source.at(10, 10, 1) = std::numeric_limits<float>::quiet_NaN();
  auto out = aq::test::run_node("edge", {{"image", input}, {"source", source}}, {},
                                options_for(input, "float"));
  ASSERT_TRUE(out.ok()) << out.message();
  EXPECT_TRUE(aq::test::all_finite(*out));
}

TEST(Edge, OnePixelImageHasNoEdges) {
  const ImageF input = aq::test::constant_image(1, 1, 0.2f, 0.4f, 0.6f, 1.0f);
  for (const char* kernel : {"laplacian", "sobel"}) {
    auto out =
        aq::test::run_node("edge", {{"image", input}}, {{"kernel", kernel}, {"threshold", 0.0}},
                           options_for(input, "float"));
    ASSERT_TRUE(out.ok()) << out.message();
    EXPECT_EQ(aq::test::max_abs_diff(*out, input), 0.0) << kernel;
  }
}

// edge_detect → edge_apply is `edge` in two nodes: the weight written as a 32-bit float and
// read at the pixel gives the same bits as `edge` computing it in place, for both kernels, a
// source of the image's size and one stretched over it, and against the reference.
TEST(Edge, DetectThenApplyEqualsEdge) {
  const ImageF image = blocky_image(64, 48);
  for (const int source_width : {64, 32}) {
    const ImageF source = blocky_image(source_width, source_width * 3 / 4);
    for (const char* kernel : {"laplacian", "sobel"}) {
      const nlohmann::json detection = {{"kernel", kernel}, {"threshold", 0.05}, {"softness", 0.3}};
      nlohmann::json edge_params = detection;
      edge_params["factor"] = 0.4;
      const nlohmann::json graph = {
          {"aquarelle", 1},
          {"settings", {{"width", 64}, {"height", 48}, {"precision", "float"}}},
          {"nodes",
           {{"image", {{"type", "image_input"}, {"params", {{"name", "image"}}}}},
            {"source", {{"type", "image_input"}, {"params", {{"name", "source"}}}}},
            {"one",
             {{"type", "edge"},
              {"params", edge_params},
              {"inputs", {{"image", "image.image"}, {"source", "source.image"}}}}},
            {"edges",
             {{"type", "edge_detect"},
              {"params", detection},
              {"inputs", {{"source", "source.image"}}}}},
            {"two",
             {{"type", "edge_apply"},
              {"params", {{"factor", 0.4}}},
              {"inputs", {{"image", "image.image"}, {"edges", "edges.edges"}}}}}}},
          {"output", "two.image"}};
      const std::map<std::string, ImageF> images = {{"image", image}, {"source", source}};
      aq::test::RenderOptions options;
      options.height = 48;
      auto two = aq::test::render_graph(graph.dump(), options, images);
      options.output = "one.image";
      auto one = aq::test::render_graph(graph.dump(), options, images);
      ASSERT_TRUE(two.ok()) << two.message();
      ASSERT_TRUE(one.ok()) << one.message();
      EXPECT_EQ(aq::test::max_abs_diff(*two, *one), 0.0) << kernel << ", source " << source_width;
      aq::reference::EdgeParams params;
      params.kernel = kernel_of(kernel);
      params.factor = 0.4;
      params.threshold = 0.05;
      params.softness = 0.3;
      const ImageF expected = aq::reference::edge_darkening(image, &source, params);
      EXPECT_LE(aq::test::max_abs_diff(*two, expected), 1e-5) << kernel;
      EXPECT_GT(aq::test::max_abs_diff(*two, image), 0.1) << "something was darkened";
    }
  }
}

}  // namespace

namespace {

// Issue 37: watercolor darkens edges where washes meet (objects, colour regions), not along the
// light's own cel bands. In graphs/underwater.json at 160x90, inside every object (pixels whose
// 3x3 neighbourhood holds one non-zero id: a continuous cel-shaded surface, bands and caustics
// included) the edge node darkens nothing: its output equals its input there. Its source is the
// light's `plain` output holding the object regions (cel_light `plain` = regions, a flat colour
// per id); with the light without caustics there instead, as before, the floor's cel bands
// were drawn as contour lines (1396 of the 5940 inside pixels darkened, measured).
TEST(Edge, TheFlagshipDrawsNoLineInsideAContinuousSurface) {
  aq::test::RenderOptions options;
  options.width = 160;
  options.height = 90;
  options.frame = 12;
  const std::string graph = aq::test::source_path("graphs/underwater.json");
  options.output = "edge.image";
  auto edged = aq::test::render_graph_file(graph, options);
  options.output = "wobble.image";
  auto wobbled = aq::test::render_graph_file(graph, options);
  options.output = "gbuf.id";
  auto id = aq::test::render_graph_file(graph, options);
  ASSERT_TRUE(edged.ok()) << edged.message();
  ASSERT_TRUE(wobbled.ok()) << wobbled.message();
  ASSERT_TRUE(id.ok()) << id.message();
  int inside = 0, darkened_inside = 0, darkened_at_borders = 0;
  for (int y = 1; y + 1 < options.height; ++y) {
    for (int x = 1; x + 1 < options.width; ++x) {
      bool one_object = id->at(x, y, 0) >= 0.5f;
      for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx)
          one_object = one_object && id->at(x + dx, y + dy, 0) == id->at(x, y, 0);
      const bool darkened = edged->at(x, y, 1) < 0.99f * wobbled->at(x, y, 1) - 1e-6f;
      if (one_object) {
        ++inside;
        darkened_inside += darkened;
      } else {
        darkened_at_borders += darkened;
      }
    }
  }
  EXPECT_GT(inside, options.width * options.height / 3) << "the objects cover the frame";
  EXPECT_EQ(darkened_inside, 0) << "of " << inside << " pixels inside objects";
  EXPECT_GT(darkened_at_borders, 100) << "the objects' outlines are darkened";
}

}  // namespace
