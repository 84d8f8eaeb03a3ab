// `light_shafts` (issue 38: seed 001's god rays): the light the water scatters towards the eye
// where the caustics focus it. Against the CPU reference written from the README's maths
// (reference/src/light_shafts.cpp), and two properties that need no reference: a uniform
// caustic excess k gives exactly k (1 - exp(-sigma D)) whatever the number of steps (the
// segments' weights telescope), and no caustics above flat water (c = 1) add nothing.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include <cmath>
#include <string>

#include "aquarelle/reference/light_shafts.h"
#include "support/harness.h"

namespace {

using aq::ImageF;

constexpr int kSize = 64;
const double kEye[3] = {0.0, 1.0, 6.0}, kTarget[3] = {0.0, 0.5, 0.0};
constexpr double kFov = 60.0, kWater = 8.0, kTile = 3.0;
const double kLight[3] = {0.6, -0.8, 0.0};  // unit: the scene keeps it as given

// A caustic texture with sharp bright lines (values 0.4 .. 3) on a 16 x 16 tile.
ImageF caustic_lines() {
  ImageF c(16, 16, 4, 1.0f);
  for (int y = 0; y < 16; ++y)
    for (int x = 0; x < 16; ++x) {
      const double v = 0.4 + 2.6 * std::pow(std::abs(std::sin(0.9 * x + 0.3 * y)), 8.0) +
                       0.5 * (((x * 5 + y * 3) % 7) == 0);
      for (int k = 0; k < 3; ++k) c.at(x, y, k) = static_cast<float>(v * (1.0 + 0.1 * k));
    }
  return c;
}

// Positions: a wall at z = -2 over the left half (alpha 1), background (alpha 0) on the right.
ImageF wall_positions() {
  ImageF p(kSize, kSize, 4, 0.0f);
  for (int y = 0; y < kSize; ++y)
    for (int x = 0; x < kSize / 2; ++x) {
      p.at(x, y, 0) = static_cast<float>(-3.0 + 6.0 * x / kSize);
      p.at(x, y, 1) = static_cast<float>(-1.0 + 5.0 * y / kSize);
      p.at(x, y, 2) = -2.0f;
      p.at(x, y, 3) = 1.0f;
    }
  return p;
}

std::string graph(const nlohmann::json& params) {
  nlohmann::json g = {{"aquarelle", 1},
                      {"nodes",
                       {{"picture", {{"type", "image_input"}, {"params", {{"name", "picture"}}}}},
                        {"position", {{"type", "image_input"}, {"params", {{"name", "position"}}}}},
                        {"caustics", {{"type", "image_input"}, {"params", {{"name", "caustics"}}}}},
                        {"join",
                         {{"type", "scene_join"},
                          {"params",
                           {{"camera_position", {kEye[0], kEye[1], kEye[2]}},
                            {"camera_target", {kTarget[0], kTarget[1], kTarget[2]}},
                            {"fov", kFov},
                            {"light_direction", {kLight[0], kLight[1], kLight[2]}},
                            {"light_color", {1.0, 0.9, 0.8}},
                            {"light_intensity", 1.0},
                            {"water_height", kWater},
                            {"caustic_tile", kTile},
                            {"environment", "none"}}}}},
                        {"shafts",
                         {{"type", "light_shafts"},
                          {"params", params},
                          {"inputs",
                           {{"image", "picture.image"},
                            {"position", "position.image"},
                            {"scene", "join.scene"},
                            {"caustics", "caustics.image"}}}}}}},
                      {"output", "shafts.image"}};
  return g.dump();
}

ImageF render(const nlohmann::json& params, const ImageF& caustics) {
  aq::test::RenderOptions options;
  options.width = options.height = kSize;
  const std::map<std::string, ImageF> images{{"picture", aq::test::gradient_image(kSize, kSize)},
                                             {"position", wall_positions()},
                                             {"caustics", caustics}};
  auto image = aq::test::render_graph(graph(params), options, images);
  EXPECT_TRUE(image.ok()) << (image.ok() ? "" : image.message());
  return image.ok() ? *image : ImageF();
}

aq::reference::LightShaftsParams reference_params(double strength, double extinction, int steps,
                                                  double max_distance) {
  aq::reference::LightShaftsParams p;
  p.eye = {kEye[0], kEye[1], kEye[2]};
  p.target = {kTarget[0], kTarget[1], kTarget[2]};
  p.fov_degrees = kFov;
  p.light_direction = {kLight[0], kLight[1], kLight[2]};
  p.light_color = {1.0, 0.9, 0.8};
  p.water_height = kWater;
  p.tile = kTile;
  p.strength = strength;
  p.extinction = extinction;
  p.steps = steps;
  p.max_distance = max_distance;
  return p;
}

TEST(LightShafts, MatchesTheReferenceOnAWallAndOpenWater) {
  const ImageF caustics = caustic_lines();
  const nlohmann::json params = {
      {"strength", 2.0}, {"extinction", 0.15}, {"steps", 16}, {"max_distance", 30.0}};
  const ImageF got = render(params, caustics);
  ASSERT_EQ(got.width, kSize);
  const ImageF want =
      aq::reference::light_shafts(aq::test::gradient_image(kSize, kSize), wall_positions(),
                                  caustics, reference_params(2.0, 0.15, 16, 30.0));
  EXPECT_LT(aq::test::max_abs_diff(got, want, 3), 2e-3);
  // Not a blank: the shafts vary across the picture by much more than the tolerance.
  const ImageF plain = aq::test::gradient_image(kSize, kSize);
  double lo = 1e9, hi = -1e9;
  for (int y = 0; y < kSize; ++y)
    for (int x = 0; x < kSize; ++x) {
      const double added = got.at(x, y, 0) - plain.at(x, y, 0);
      lo = std::min(lo, added), hi = std::max(hi, added);
    }
  EXPECT_GT(hi - lo, 0.05);
  EXPECT_GE(lo, -1e-6) << "the shafts only add light";
}

// A uniform excess k: sum over segments of k (e^{-s t_k} - e^{-s t_{k+1}}) = k (1 - e^{-s D}),
// exactly, for 1 step as for 64. On the wall D is the distance to it; on open water max_distance.
TEST(LightShafts, UniformCausticsGiveTheClosedFormWhateverTheSteps) {
  const ImageF uniform(8, 8, 4, 1.5f);  // excess 0.5 in every channel
  const ImageF positions = wall_positions();
  const ImageF plain = aq::test::gradient_image(kSize, kSize);
  const double colour[3] = {1.0, 0.9, 0.8};
  for (int steps : {1, 64}) {
    const ImageF got =
        render({{"strength", 1.0}, {"extinction", 0.2}, {"steps", steps}, {"max_distance", 12.0}},
               uniform);
    ASSERT_EQ(got.width, kSize);
    double largest = 0.0;
    for (int y = 0; y < kSize; ++y)
      for (int x = 0; x < kSize; ++x) {
        double distance = 12.0;
        if (positions.at(x, y, 3) == 1.0f) {
          const double dx = positions.at(x, y, 0) - kEye[0], dy = positions.at(x, y, 1) - kEye[1],
                       dz = positions.at(x, y, 2) - kEye[2];
          distance = std::sqrt(dx * dx + dy * dy + dz * dz);
        }
        // Only water scatters: every sample of these rays is below the water (y < 8).
        const double added = 0.5 * (1.0 - std::exp(-0.2 * distance));
        for (int c = 0; c < 3; ++c) {
          largest =
              std::max(largest, std::abs(got.at(x, y, c) - plain.at(x, y, c) - colour[c] * added));
        }
      }
    EXPECT_LT(largest, 1e-4) << steps << " steps";
  }
}

TEST(LightShafts, FlatWaterAddsNothing) {
  const ImageF flat(8, 8, 4, 1.0f);
  const ImageF got = render({{"strength", 5.0}, {"steps", 8}}, flat);
  ASSERT_EQ(got.width, kSize);
  EXPECT_EQ(aq::test::max_abs_diff(got, aq::test::gradient_image(kSize, kSize)), 0.0);
}

}  // namespace
