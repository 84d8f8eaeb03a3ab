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

aq_camera camera(const float* eye = kEye, const float* target = kTarget) {
  aq_camera c{};
  for (int k = 0; k < 3; ++k) {
    c.position[k] = eye[k];
    c.target[k] = target[k];
  }
  c.up[1] = 1.0f;
  c.fov_y_degrees = static_cast<float>(kFov);
  return c;
}

// resolution 1: a ray per pixel, the exact march the reference computes.
aq::Result<ImageF> run(const ImageF& image, const ImageF* depth, const CloudsParams& p, int frame,
                       const char* precision = "float", int resolution = 1, const float* eye = kEye,
                       const float* target = kTarget) {
  nlohmann::json nodes;
  nodes["image"] = {{"type", "image_input"}, {"params", {{"name", "image"}}}};
  nodes["join"] = {{"type", "scene_join"},
                   {"params",
                    {{"camera_position", {eye[0], eye[1], eye[2]}},
                     {"camera_target", {target[0], target[1], target[2]}},
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
                       {"max_distance", p.max_distance},
                       {"warp", p.warp},
                       {"resolution", resolution}}}};
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

// The waterfall's spray: high-frequency FBM rising, fading with the distance from the fall's
// base, that distance distorted by animated FBM (warp); the exact march against the reference.
TEST(Clouds, WarpedSprayMatchesReference) {
  const ImageF image = aq::test::random_image(40, 30, 35);
  const ImageF depth = ramp_depth(40, 30);
  CloudsParams p;
  p.falloff = 2;
  p.centre = {0.0, 2.0, 0.0};
  p.falloff_length = 2.5;
  p.warp = 0.8;
  p.scale = 2.0;
  p.density = 1.5;
  p.drift = {0.0, 0.6, 0.0};
  p.steps = 24;
  const ImageF expected = aq::reference::clouds(image, camera(), &depth, 0.5, p);
  auto got = run(image, &depth, p, 13);
  ASSERT_TRUE(got.ok()) << got.message();
  EXPECT_LE(aq::test::mean_abs_diff(*got, expected), 2e-4);
  EXPECT_LE(aq::test::max_abs_diff(*got, expected), 2e-3);
  EXPECT_GT(aq::test::mean_abs_diff(*got, image), 1e-3);
  // Animated: half a second later the spray has moved.
  auto later = run(image, &depth, p, 25);
  ASSERT_TRUE(later.ok());
  EXPECT_GT(aq::test::mean_abs_diff(*got, *later), 1e-3);
}

// One ray per 4x4 pixels (the default), τ upsampled by depth, against a ray per pixel: close
// everywhere, and a near surface in front of the volume is not smeared with the sky's τ.
TEST(Clouds, CoarseMarchFollowsTheDepthAndStaysClose) {
  const int w = 96, h = 64;
  const ImageF image = aq::test::constant_image(w, h, 0.1f, 0.2f, 0.3f);
  ImageF depth(w, h, 1);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) depth.at(x, y, 0) = (x / 7 + y / 5) % 3 == 0 ? 1.5f : 200.0f;
  CloudsParams p;
  p.falloff_start = 1.0;
  p.density = 0.6;
  const ImageF exact_ref = aq::reference::clouds(image, camera(), &depth, 0.25, p);
  auto exact = run(image, &depth, p, 7);
  auto coarse = run(image, &depth, p, 7, "float", 4);
  ASSERT_TRUE(exact.ok() && coarse.ok()) << exact.message() << coarse.message();
  EXPECT_LE(aq::test::mean_abs_diff(*exact, exact_ref), 2e-4);
  const double mean = aq::test::mean_abs_diff(*coarse, *exact);
  const double max = aq::test::max_abs_diff(*coarse, *exact);
  std::printf("[clouds] resolution 4 against 1: max %.3g mean %.3g\n", max, mean);
  EXPECT_LE(mean, 0.01);
  // The worst pixel: sky whose four nearest cells' rays all ended on a near block (blocks of
  // 7x5 pixels against cells of 4x4): it takes the nearest-depth cell's τ. Measured 0.27.
  EXPECT_LE(max, 0.35);
  // Near pixels (depth 1.5) hold almost no volume: none of them takes the sky's opacity.
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x)
      if (depth.at(x, y, 0) < 2.0f) {
        ASSERT_NEAR(coarse->at(x, y, 0), exact->at(x, y, 0), 0.05) << x << "," << y;
      }
}

// Where is the volume's opacity centred in the picture (opacity: red of a black image under a
// white volume), in pixels, and where does the camera project the world point `p`?
std::pair<double, double> opacity_centroid(const ImageF& im) {
  double sx = 0, sy = 0, s = 0;
  for (int y = 0; y < im.height; ++y)
    for (int x = 0; x < im.width; ++x) {
      const double a = im.at(x, y, 0);
      sx += a * x;
      sy += a * y;
      s += a;
    }
  return {sx / s, sy / s};
}

std::pair<double, double> project(const aq_camera& c, const double p[3], int w, int h) {
  const double eye[3] = {c.position[0], c.position[1], c.position[2]};
  double f[3], r[3], u[3], v[3];
  for (int k = 0; k < 3; ++k) f[k] = c.target[k] - eye[k], v[k] = p[k] - eye[k];
  const double fl = std::sqrt(f[0] * f[0] + f[1] * f[1] + f[2] * f[2]);
  for (double& x : f) x /= fl;
  r[0] = -f[2], r[1] = 0.0, r[2] = f[0];  // forward × (0, 1, 0)
  const double rl = std::sqrt(r[0] * r[0] + r[2] * r[2]);
  for (double& x : r) x /= rl;
  u[0] = r[1] * f[2] - r[2] * f[1], u[1] = r[2] * f[0] - r[0] * f[2],
  u[2] = r[0] * f[1] - r[1] * f[0];
  auto dot = [](const double* a, const double* b) {
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
  };
  const double t = std::tan(c.fov_y_degrees * 3.14159265358979323846 / 360.0);
  const double nx = dot(v, r) / dot(v, f) / (t * w / h), ny = dot(v, u) / dot(v, f) / t;
  return {(nx + 1.0) / 2.0 * w - 0.5, (ny + 1.0) / 2.0 * h - 0.5};
}

// Seed 002's note: its volume sat in camera space and slid when the camera moved. This one is
// anchored in the world: from two cameras the ball of spray is found where each projects it.
TEST(Clouds, VolumeStaysWhereTheWorldPutsItWhenTheCameraMoves) {
  const int w = 96, h = 64;
  const ImageF black = aq::test::constant_image(w, h, 0.0f, 0.0f, 0.0f);
  CloudsParams p;
  p.noise = 0.0;
  p.falloff = 2;
  p.centre = {1.0, 2.6, 0.5};
  p.falloff_length = 0.7;
  p.density = 3.0;
  p.light_color = {1.0, 1.0, 1.0};
  const float eyes[2][3] = {{0.0f, 2.0f, 6.0f}, {-2.5f, 3.5f, 4.5f}};
  const float targets[2][3] = {{0.0f, 2.5f, 0.0f}, {0.5f, 2.0f, 0.0f}};
  std::pair<double, double> seen[2];
  for (int i = 0; i < 2; ++i) {
    auto got = run(black, nullptr, p, 1, "float", 4, eyes[i], targets[i]);
    ASSERT_TRUE(got.ok()) << got.message();
    seen[i] = opacity_centroid(*got);
    const auto expected = project(camera(eyes[i], targets[i]), p.centre.data(), w, h);
    EXPECT_NEAR(seen[i].first, expected.first, 1.0) << "camera " << i;
    EXPECT_NEAR(seen[i].second, expected.second, 1.0) << "camera " << i;
  }
  EXPECT_GT(std::abs(seen[0].first - seen[1].first), 2.5);  // the camera moved: so did the ball
}

}  // namespace
