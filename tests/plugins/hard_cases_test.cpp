// Hard cases for every image-to-image node, under EGL and OSMesa: tiny and odd sizes, constant
// images, values far outside [0, 1], NaN and Inf pixels (which must stay local), and the GL
// size limit (its edge works, one past it is a clear error). Each assertion checks values.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "support/harness.h"

namespace aq::test {
namespace {

struct Case {
  std::string gl;
  std::string node;
};

std::string case_name(const ::testing::TestParamInfo<Case>& info) {
  return info.param.gl + "_" + info.param.node;
}

// Nodes whose output for a constant image is that same constant.
bool keeps_constants(const std::string& node) {
  return node == "erode" || node == "dilate" || node == "blur" || node == "wobble" ||
         node == "edge" || node == "edge_darkening" || node == "tremor";
}

// How far (pixels) a node may carry a value from one pixel to another with default params.
int reach(const std::string& node) {
  if (node == "blur") return 20;  // 4 sigma of sigma 4
  if (node == "wobble") return 12;
  // A bad texel stops the darkening (d = 0) within the blur's footprint: by default the blur
  // runs on 2x2 cells (the cell average, 6 cells of 4 sigma at sigma 1.42 cells, the bilinear
  // read-back): measured up to 18 px (on every pixel it was 14: 4 sigma = 12 plus its last taps).
  if (node == "edge_darkening") return 18;
  return 3;
}

class HardCases : public ::testing::TestWithParam<Case> {
 protected:
  RenderOptions options(int w, int h) const {
    RenderOptions o;
    o.width = w;
    o.height = h;
    o.gl = GetParam().gl;
    return o;
  }
  Result<ImageF> run(const ImageF& image) const {
    return run_node(GetParam().node, {{"image", image}}, nlohmann::json::object(),
                    options(image.width, image.height));
  }
};

TEST_P(HardCases, TinyAndOddSizesKeepTheirSize) {
  for (auto [w, h] : {std::pair{1, 1}, {1, 9}, {9, 1}, {13, 7}, {2, 3}}) {
    ImageF input = random_image(w, h, 11);
    auto out = run(input);
    ASSERT_TRUE(out.ok()) << w << "x" << h << ": " << out.message();
    EXPECT_EQ(out->width, w);
    EXPECT_EQ(out->height, h);
    EXPECT_TRUE(all_finite(*out)) << w << "x" << h;
  }
}

TEST_P(HardCases, ConstantImages) {
  const std::string& node = GetParam().node;
  ImageF input = constant_image(24, 16, 0.6f, 0.3f, 0.15f);
  auto out = run(input);
  ASSERT_TRUE(out.ok()) << out.message();
  if (keeps_constants(node)) {
    EXPECT_LE(max_abs_diff(*out, input, 3), 1e-5) << node << " changed a constant image";
  } else if (node == "tint") {
    const float tint[3] = {0.0f, 0.07f, 0.1f}, amount = 0.2f;
    for (int c = 0; c < 3; ++c) {
      EXPECT_NEAR(out->at(5, 5, c), input.at(5, 5, c) + (tint[c] - input.at(5, 5, c)) * amount,
                  1e-5);
    }
  } else if (node == "vignette") {
    for (size_t i = 0; i < out->pixels.size(); ++i) {
      if (i % 4 == 3) continue;
      EXPECT_LE(out->pixels[i], input.pixels[i] + 1e-6f);
      EXPECT_GE(out->pixels[i], input.pixels[i] * 0.3f - 1e-6f);
    }
  } else if (node == "pigment") {
    for (size_t i = 0; i < out->pixels.size(); ++i) {
      EXPECT_GE(out->pixels[i], 0.0f);
      EXPECT_LE(out->pixels[i], 1.0f);
    }
  }
}

TEST_P(HardCases, ValuesFarOutsideTheUnitRange) {
  const std::string& node = GetParam().node;
  ImageF input = random_image(20, 20, 5, -1.0f, 1.0e4f);
  auto out = run(input);
  ASSERT_TRUE(out.ok()) << out.message();
  EXPECT_TRUE(all_finite(*out));
  if (node == "erode" || node == "dilate") {
    // Results are values of the input (min or max of a window): never outside its range.
    for (size_t i = 0; i < out->pixels.size(); ++i) {
      EXPECT_GE(out->pixels[i], -1.0f);
      EXPECT_LE(out->pixels[i], 1.0e4f);
    }
  }
}

TEST_P(HardCases, NanAndInfStayLocal) {
  const std::string& node = GetParam().node;
  ImageF clean = random_image(64, 64, 9);
  ImageF dirty = clean;
  const float nan = std::numeric_limits<float>::quiet_NaN();
  const float inf = std::numeric_limits<float>::infinity();
  for (int c = 0; c < 3; ++c) {
    dirty.at(4, 4, c) = nan;
    dirty.at(59, 59, c) = inf;
    dirty.at(59, 4, c) = -inf;
  }
  auto a = run(clean);
  auto b = run(dirty);
  ASSERT_TRUE(a.ok() && b.ok()) << (a.ok() ? b.message() : a.message());
  const int r = reach(node);
  double worst = 0;
  for (int y = 0; y < 64; ++y) {
    for (int x = 0; x < 64; ++x) {
      auto near = [&](int px, int py) { return std::abs(x - px) <= r && std::abs(y - py) <= r; };
      if (near(4, 4) || near(59, 59) || near(59, 4)) continue;
      for (int c = 0; c < 4; ++c) {
        ASSERT_TRUE(std::isfinite(b->at(x, y, c))) << node << " spread NaN/Inf to " << x << ","
                                                   << y;
        worst = std::max(worst, static_cast<double>(std::abs(a->at(x, y, c) - b->at(x, y, c))));
      }
    }
  }
  EXPECT_LE(worst, 1e-5) << node << ": pixels far from the bad ones changed";
}

std::vector<Case> all_cases() {
  std::vector<Case> cases;
  for (const char* gl : {"egl", "osmesa"}) {
    for (const char* node :
         {"blur", "dilate", "edge", "erode", "pigment", "tint", "vignette", "wobble",
          "edge_darkening", "tremor"}) {
      cases.push_back({gl, node});
    }
  }
  return cases;
}

INSTANTIATE_TEST_SUITE_P(Nodes, HardCases, ::testing::ValuesIn(all_cases()), case_name);

class SizeLimit : public ::testing::TestWithParam<std::string> {};

TEST_P(SizeLimit, LargestTextureWorksOnePastIsAClearError) {
  RenderOptions o;
  o.gl = GetParam();
  o.width = 16384;  // llvmpipe's GL_MAX_TEXTURE_SIZE
  o.height = 1;
  auto edge = run_node("noise", {}, {{"type", "perlin"}}, o);
  ASSERT_TRUE(edge.ok()) << edge.message();
  EXPECT_EQ(edge->width, 16384);
  EXPECT_TRUE(all_finite(*edge));
  o.width = 16385;
  auto past = run_node("noise", {}, {{"type", "perlin"}}, o);
  ASSERT_FALSE(past.ok());
  EXPECT_NE(past.message().find("node 'node' (noise)"), std::string::npos) << past.message();
  EXPECT_NE(past.message().find("16385x1"), std::string::npos) << past.message();
  EXPECT_NE(past.message().find("1x1 to 16384x16384"), std::string::npos) << past.message();
}

INSTANTIATE_TEST_SUITE_P(Backends, SizeLimit, ::testing::Values("egl", "osmesa"));

}  // namespace
}  // namespace aq::test
