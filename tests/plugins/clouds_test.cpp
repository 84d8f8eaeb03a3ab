// Headless tests of the `clouds` node against reference/clouds.h: a homogeneous medium
// (Beer–Lambert, exact whatever the steps) stopped by the depth image, FBM clouds with the
// height falloff, the stepped threshold and drift; zero density bit-exact; 1x1; NaN depth and
// colour stay put.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "aquarelle/reference/clouds.h"
#include "support/harness.h"

namespace {

using aq::ImageF;
using aq::reference::CloudsParams;

constexpr float kEye[3] = {0.0f, 2.0f, 6.0f};
constexpr float kTarget[3] = {0.0f, 2.5f, 0.0f};
constexpr double kFov = 50.0;

aq_camera camera() {
  aq_camera c{};
  for (int k = 0; k < 3; ++k) {
    c.position[k] = kEye[k];
    c.target[k] = kTarget[k];
  }
  c.up[1] = 1.0f;
  c.fov_y_degrees = static_cast<float>(kFov);
  return c;
}

aq::Result<ImageF> run(const ImageF& image, const ImageF* depth, const CloudsParams& p, int frame,
                       const char* precision = "float") {
  nlohmann::json nodes;
  nodes["image"] = {{"type", "image_input"}, {"params", {{"name", "image"}}}};
  nodes["join"] = {{"type", "scene_join"},
                   {"params",
                    {{"camera_position", {kEye[0], kEye[1], kEye[2]}},
                     {"camera_target", {kTarget[0], kTarget[1], kTarget[2]}},
                     {"fov", kFov}}}};
  nlohmann::json inputs = {{"image", "image.image"}, {"scene", "join.scene"}};
  std::map<std::string, ImageF> images{{"image", image}};
  if (depth) {
    nodes["depth"] = {{"type", "image_input"}, {"params", {{"name", "depth"}}}};
    inputs["depth"] = "depth.image";
    images["depth"] = *depth;
  }
  const char* falloffs[] = {"none", "height", "distance"};
  nodes["clouds"] = {{"type", "clouds"},
                     {"inputs", inputs},
                     {"params",
                      {{"density", p.density},
                       {"noise", p.noise},
                       {"scale", p.scale},
                       {"octaves", p.octaves},
                       {"threshold", p.threshold},
                       {"falloff", falloffs[p.falloff]},
                       {"falloff_start", p.falloff_start},
                       {"falloff_length", p.falloff_length},
                       {"centre", {p.centre[0], p.centre[1], p.centre[2]}},
                       {"drift", {p.drift[0], p.drift[1], p.drift[2]}},
                       {"light_color", {p.light_color[0], p.light_color[1], p.light_color[2]}},
                       {"steps", p.steps},
                       {"max_distance", p.max_distance}}}};
  aq::test::RenderOptions options;
  options.width = image.width;
  options.height = image.height;
  options.precision = precision;
  options.frame = frame;
  const std::string graph =
      nlohmann::json({{"aquarelle", 1}, {"nodes", nodes}, {"output", "clouds.image"}}).dump();
  return aq::test::render_graph(graph, options, images);
}

ImageF ramp_depth(int w, int h) {
  ImageF depth(w, h, 1);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) depth.at(x, y, 0) = x < w / 3 ? 200.0f : 1.0f + 0.2f * x;
  return depth;
}

TEST(Clouds, HomogeneousMediumIsBeerLambertUpToTheSurface) {
  const ImageF image = aq::test::random_image(40, 30, 31);
  const ImageF depth = ramp_depth(40, 30);
  CloudsParams p;
  p.noise = 0.0;
  p.falloff = 0;
  p.density = 0.15;
  p.steps = 3;  // a homogeneous medium is exact with any number of steps
  const ImageF expected = aq::reference::clouds(image, camera(), &depth, 0.0, p);
  auto got = run(image, &depth, p, 1);
  ASSERT_TRUE(got.ok()) << got.message();
  const double error = aq::test::max_abs_diff(*got, expected);
  EXPECT_LE(error, 2e-5);
  std::printf("[clouds] homogeneous float max abs %.3g\n", error);
  // Nearer surfaces are less covered than the far background (max_distance 40).
  EXPECT_GT(std::abs(got->at(2, 15, 0) - image.at(2, 15, 0)),
            std::abs(got->at(30, 15, 0) - image.at(30, 15, 0)));
}

TEST(Clouds, NoisyCloudsWithFalloffThresholdAndDrift) {
  const ImageF image = aq::test::random_image(40, 30, 32);
  const ImageF depth = ramp_depth(40, 30);
  for (double threshold : {0.0, 0.45}) {
    CloudsParams p;
    p.threshold = threshold;
    p.steps = 24;
    p.falloff_start = 1.5;
    const ImageF expected = aq::reference::clouds(image, camera(), &depth, 0.5, p);
    auto got = run(image, &depth, p, 13);  // frame 13 at 24 fps: t = 0.5 s
    ASSERT_TRUE(got.ok()) << got.message();
    const double error = aq::test::max_abs_diff(*got, expected);
    // Float noise and marching against double; the threshold's step can flip one sample.
    EXPECT_LE(aq::test::mean_abs_diff(*got, expected), 2e-4) << threshold;
    EXPECT_LE(error, threshold > 0.0 ? 0.05 : 2e-3) << threshold;
    std::printf("[clouds] threshold %.2f float max abs %.3g mean %.3g\n", threshold, error,
                aq::test::mean_abs_diff(*got, expected));
    EXPECT_GT(aq::test::mean_abs_diff(*got, image), 1e-3);  // clouds are there
  }
}

TEST(Clouds, ZeroDensityIsBitExactIdentity) {
  const ImageF image = aq::test::random_image(21, 13, 33, -1.0f, 4.0f);
  CloudsParams p;
  p.density = 0.0;
  auto got = run(image, nullptr, p, 5);
  ASSERT_TRUE(got.ok()) << got.message();
  EXPECT_EQ(aq::test::max_abs_diff(*got, image), 0.0);
  CloudsParams below;  // density > 0 but all of it below the sky's falloff: τ = 0 everywhere
  below.falloff_start = 1000.0;
  auto empty = run(image, nullptr, below, 5);
  ASSERT_TRUE(empty.ok()) << empty.message();
  EXPECT_EQ(aq::test::max_abs_diff(*empty, image), 0.0);
}

TEST(Clouds, OnePixelAndNaN) {
  const ImageF one = aq::test::constant_image(1, 1, 0.2f, 0.4f, 0.6f);
  CloudsParams p;
  p.noise = 0.0;
  p.falloff = 0;
  auto got = run(one, nullptr, p, 1);
  ASSERT_TRUE(got.ok()) << got.message();
  EXPECT_LE(aq::test::max_abs_diff(*got, aq::reference::clouds(one, camera(), nullptr, 0.0, p)),
            2e-5);
  ImageF image = aq::test::random_image(16, 16, 34);
  image.at(4, 4, 0) = std::numeric_limits<float>::quiet_NaN();
  ImageF depth = ramp_depth(16, 16);
  depth.at(8, 8, 0) = std::numeric_limits<float>::quiet_NaN();
  auto nan = run(image, &depth, {}, 1);
  ASSERT_TRUE(nan.ok()) << nan.message();
  int non_finite = 0;
  for (int y = 0; y < 16; ++y)
    for (int x = 0; x < 16; ++x)
      for (int c = 0; c < 4; ++c) non_finite += std::isfinite(nan->at(x, y, c)) ? 0 : 1;
  EXPECT_EQ(non_finite, 1);
}

}  // namespace
