// Headless tests of the `fog` node against the CPU reference (reference/fog.h):
// reference comparison in float and half precision, monotonic in depth, density 0 identity,
// emissive objects glowing through the fog, background and non-finite depth, bad id lists.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "aquarelle/reference/fog.h"
#include "support/harness.h"

namespace {

using aq::ImageF;
using aq::reference::FogParams;

nlohmann::json to_json(const FogParams& p) {
  std::string ids;
  for (int id : p.emissive_ids) ids += (ids.empty() ? "" : ", ") + std::to_string(id);
  return {{"color", {p.color[0], p.color[1], p.color[2]}},
          {"density", p.density},
          {"exponent", p.exponent},
          {"emissive_ids", ids},
          {"emission", p.emission}};
}

aq::Result<ImageF> run(const ImageF& image, const ImageF& depth, const ImageF* id,
                       const nlohmann::json& params, const char* precision = "float") {
  std::map<std::string, ImageF> inputs{{"image", image}, {"depth", depth}};
  if (id != nullptr) inputs.emplace("id", *id);
  aq::test::RenderOptions options;
  options.precision = precision;
  return aq::test::run_node("fog", inputs, params, options);
}

// Depth from 0.5 to `far` along x, in channel 0.
ImageF depth_ramp(int width, int height, double far) {
  ImageF depth(width, height, 4, 1.0f);
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x)
      depth.at(x, y, 0) = static_cast<float>(0.5 + (far - 0.5) * x / (width - 1));
  return depth;
}

// Object ids in horizontal bands of 8 rows: 0 (background), 1, 2, 3, ...
ImageF id_bands(int width, int height) {
  ImageF id(width, height, 4, 0.0f);
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) id.at(x, y, 0) = static_cast<float>(y / 8);
  return id;
}

TEST(Fog, MatchesReferenceInFloatAndHalf) {
  const ImageF image = aq::test::random_image(64, 48, 31);
  ImageF depth = depth_ramp(64, 48, 80.0);
  for (int y = 0; y < 48; ++y) depth.at(0, y, 0) = 0.0f;  // a column of background
  const ImageF id = id_bands(64, 48);
  FogParams params;
  params.emissive_ids = {2, 4};
  const ImageF expected = aq::reference::fog(image, depth, &id, params);
  auto got = run(image, depth, &id, to_json(params));
  ASSERT_TRUE(got.ok()) << got.message();
  EXPECT_LE(aq::test::max_abs_diff(*got, expected), 1e-5);
  auto half = run(image, depth, &id, to_json(params), "half");
  ASSERT_TRUE(half.ok()) << half.message();
  EXPECT_LE(aq::test::max_abs_diff(*half, expected), 5e-4);
  std::printf("[fog] float max abs %.3g, half max abs %.3g\n",
              aq::test::max_abs_diff(*got, expected), aq::test::max_abs_diff(*half, expected));
}

TEST(Fog, IsMonotonicInDepth) {
  const ImageF image = aq::test::constant_image(128, 4, 0.9f, 0.5f, 0.2f);
  const ImageF depth = depth_ramp(128, 4, 150.0);
  for (double exponent : {0.5, 1.0, 2.0}) {
    FogParams params;
    params.exponent = exponent;
    auto got = run(image, depth, nullptr, to_json(params));
    ASSERT_TRUE(got.ok()) << got.message();
    // Distance to the water colour never grows with depth, and shrinks overall.
    double previous = 1e9;
    for (int x = 0; x < 128; ++x) {
      double d = 0.0;
      for (int c = 0; c < 3; ++c) d += std::abs(got->at(x, 1, c) - params.color[c]);
      EXPECT_LE(d, previous + 1e-6) << "x " << x << " exponent " << exponent;
      previous = d;
    }
    EXPECT_GT(got->at(0, 1, 0), 0.7f);    // near: close to the colour
    EXPECT_LT(got->at(127, 1, 0), 0.1f);  // far: close to the water
  }
}

TEST(Fog, DensityZeroIsExactIdentity) {
  const ImageF image = aq::test::random_image(33, 17, 32);
  FogParams params;
  params.density = 0.0;
  auto got = run(image, depth_ramp(33, 17, 50.0), nullptr, to_json(params));
  ASSERT_TRUE(got.ok()) << got.message();
  EXPECT_EQ(aq::test::max_abs_diff(*got, image), 0.0);
}

TEST(Fog, EmissiveObjectsGlowThroughTheFog) {
  const ImageF image = aq::test::constant_image(32, 32, 1.0f, 0.8f, 0.4f);
  const ImageF depth = aq::test::constant_image(32, 32, 40.0f, 0.0f, 0.0f);
  const ImageF id = id_bands(32, 32);  // ids 0..3
  FogParams params;
  params.emissive_ids = {2};
  params.emission = 0.8;
  auto got = run(image, depth, &id, to_json(params));
  ASSERT_TRUE(got.ok()) << got.message();
  const float plain = got->at(10, 12, 0);     // id 1
  const float emissive = got->at(10, 20, 0);  // id 2
  EXPECT_GT(emissive, plain + 0.3f);
  // Emission 1 ignores the fog entirely.
  params.emission = 1.0;
  auto full = run(image, depth, &id, to_json(params));
  ASSERT_TRUE(full.ok()) << full.message();
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(full->at(10, 20, c), image.at(10, 20, c), 1e-6);
  // Without the id input nothing glows (and the node still runs).
  auto no_id = run(image, depth, nullptr, to_json(params));
  ASSERT_TRUE(no_id.ok()) << no_id.message();
  EXPECT_NEAR(no_id->at(10, 20, 0), plain, 1e-6);
}

TEST(Fog, BackgroundAndNonFiniteDepthAreWaterColour) {
  const ImageF image = aq::test::random_image(8, 8, 33);
  ImageF depth(8, 8, 4, 0.0f);
  depth.at(1, 1, 0) = std::numeric_limits<float>::quiet_NaN();
  depth.at(2, 1, 0) = std::numeric_limits<float>::infinity();
  depth.at(3, 1, 0) = -5.0f;
  FogParams params;
  auto got = run(image, depth, nullptr, to_json(params));
  ASSERT_TRUE(got.ok()) << got.message();
  EXPECT_TRUE(aq::test::all_finite(*got));
  for (int x = 0; x < 4; ++x)
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(got->at(x, 1, c), params.color[c], 1e-6);
}

TEST(Fog, RejectsAMalformedIdList) {
  const ImageF image = aq::test::random_image(8, 8, 34);
  nlohmann::json params = to_json(FogParams{});
  params["emissive_ids"] = "7, jellyfish";
  auto got = run(image, depth_ramp(8, 8, 10.0), nullptr, params);
  ASSERT_FALSE(got.ok());
  EXPECT_NE(got.message().find("emissive_ids"), std::string::npos) << got.message();
}

TEST(Fog, ParameterSweepMatchesReference) {
  const ImageF image = aq::test::random_image(40, 40, 35, 0.0f, 2.0f);
  const ImageF depth = depth_ramp(40, 40, 60.0);
  const ImageF id = id_bands(40, 40);
  for (double density : {0.01, 0.1, 1.0}) {
    for (double exponent : {0.5, 1.0, 3.0}) {
      FogParams params;
      params.density = density;
      params.exponent = exponent;
      params.emissive_ids = {1, 3};
      params.emission = 0.5;
      params.color = {0.2, 0.3, 0.4};
      auto got = run(image, depth, &id, to_json(params));
      ASSERT_TRUE(got.ok()) << got.message();
      EXPECT_LE(aq::test::max_abs_diff(*got, aq::reference::fog(image, depth, &id, params)), 2e-5)
          << "density " << density << " exponent " << exponent;
    }
  }
}

}  // namespace
