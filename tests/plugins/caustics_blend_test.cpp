// `caustics`' seed-001 options (issue 38): `blend_count` images at successive times mixed with
// the seed's weights .4 .3 .2 .1 .05 normalised to sum 1, and `shift` added per channel (the
// seed's blue shift). Checked against the weighted mean, computed here in double, of the
// node's single images rendered at the blended times, and on flat water, where every image is
// exactly 1.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include <cmath>
#include <string>
#include <vector>

#include "support/harness.h"

namespace {

using aq::ImageF;

ImageF render(const nlohmann::json& params, int frame) {
  nlohmann::json graph = {{"aquarelle", 1},
                          {"nodes", {{"c", {{"type", "caustics"}, {"params", params}}}}},
                          {"output", "c.image"}};
  aq::test::RenderOptions options;
  options.width = options.height = 32;
  options.frame = frame;
  options.fps = 24.0;
  auto image = aq::test::render_graph(graph.dump(), options);
  EXPECT_TRUE(image.ok()) << (image.ok() ? "" : image.message());
  return image.ok() ? *image : ImageF();
}

const nlohmann::json kWaves = {{"resolution", 32}, {"grid", 48}, {"amplitude", 0.04}};

TEST(CausticsBlend, FiveImagesAreTheSeedsWeightedMeanPlusTheShift) {
  const double weights[5] = {0.4, 0.3, 0.2, 0.1, 0.05};
  // Image k at t - k/12 s: at 24 fps, two frames back each.
  std::vector<ImageF> singles;
  for (int k = 0; k < 5; ++k) singles.push_back(render(kWaves, 11 - 2 * k));
  nlohmann::json blended_params = kWaves;
  blended_params["blend_count"] = 5;
  blended_params["blend_interval"] = 1.0 / 12.0;
  blended_params["shift"] = {0.0, 0.05, 0.1};
  const ImageF blended = render(blended_params, 11);
  ASSERT_EQ(blended.width, 32);
  double largest = 0.0, spread = 0.0;
  for (int y = 0; y < 32; ++y) {
    for (int x = 0; x < 32; ++x) {
      for (int c = 0; c < 3; ++c) {
        double sum = 0.0;
        for (int k = 0; k < 5; ++k) sum += weights[k] * singles[k].at(x, y, c);
        const double expected = sum / 1.05 + (c == 1 ? 0.05 : c == 2 ? 0.1 : 0.0);
        largest = std::max<double>(largest, std::abs(blended.at(x, y, c) - expected));
      }
      spread = std::max<double>(spread, std::abs(singles[0].at(x, y, 0) - singles[4].at(x, y, 0)));
    }
  }
  EXPECT_GT(spread, 0.05) << "the blended times differ, or the test proves nothing";
  EXPECT_LT(largest, 1e-4);
}

TEST(CausticsBlend, FlatWaterIsOnePlusTheShiftExactly) {
  nlohmann::json params = {{"resolution", 16},
                           {"grid", 16},
                           {"amplitude", 0.0},
                           {"blend_count", 5},
                           {"shift", {0.0, 0.05, 0.1}}};
  const ImageF image = render(params, 7);
  ASSERT_EQ(image.width, 16);
  for (int y = 0; y < 16; ++y) {
    for (int x = 0; x < 16; ++x) {
      EXPECT_EQ(image.at(x, y, 0), 1.0f);
      EXPECT_FLOAT_EQ(image.at(x, y, 1), 1.05f);
      EXPECT_FLOAT_EQ(image.at(x, y, 2), 1.1f);
    }
  }
}

}  // namespace
