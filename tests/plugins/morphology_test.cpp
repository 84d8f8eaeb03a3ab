// Properties that `erode` and `dilate` must have together, whatever the size, footprint, order
// and precision: erode <= input <= dilate, opening and closing are idempotent, borders behave
// like clamp-to-edge, and the luminance order never invents a colour (the per-channel order
// does, which is the seed's §7.4 complaint and why the luminance order exists).
#include <gtest/gtest.h>

#include "aquarelle/reference/morphology.h"
#include "plugins/watercolor_test_images.h"
#include "support/harness.h"

#include <algorithm>
#include <string>
#include <tuple>

namespace {

using aq::ImageF;
using aq::test::watercolor::luminance;
using aq::test::watercolor::quantized;

struct Setting {
  int size;
  std::string footprint;
  std::string mode;
  std::string precision;
};

ImageF apply(const std::string& type, const ImageF& image, const Setting& s) {
  aq::test::RenderOptions options;
  options.width = image.width;
  options.height = image.height;
  options.precision = s.precision;
  auto out =
      aq::test::run_node(type, {{"image", image}},
                         {{"size", s.size}, {"footprint", s.footprint}, {"mode", s.mode}}, options);
  EXPECT_TRUE(out.ok()) << type << ": " << out.message();
  return out.ok() ? *out : ImageF();
}

using SettingTuple = std::tuple<int, std::string, std::string, std::string>;
class Morphology : public ::testing::TestWithParam<SettingTuple> {
 protected:
  Setting setting() const {
    const auto& [size, footprint, mode, precision] = GetParam();
    return {size, footprint, mode, precision};
  }
};

TEST_P(Morphology, ErodeBelowInputBelowDilate) {
  const Setting s = setting();
  const ImageF input = quantized(aq::test::random_image(64, 48, 21));
  const ImageF low = apply("erode", input, s);
  const ImageF high = apply("dilate", input, s);
  ASSERT_FALSE(low.empty());
  ASSERT_FALSE(high.empty());
  int violations = 0;
  for (int y = 0; y < input.height; ++y) {
    for (int x = 0; x < input.width; ++x) {
      if (s.mode == "luminance") {
        violations += luminance(low, x, y) > luminance(input, x, y);
        violations += luminance(input, x, y) > luminance(high, x, y);
      } else {
        for (int c = 0; c < 4; ++c) {
          violations += low.at(x, y, c) > input.at(x, y, c);
          violations += input.at(x, y, c) > high.at(x, y, c);
        }
      }
    }
  }
  EXPECT_EQ(violations, 0);
}

TEST_P(Morphology, OpeningAndClosingAreIdempotent) {
  const Setting s = setting();
  const ImageF input = quantized(aq::test::random_image(48, 40, 33));
  const ImageF opened = apply("dilate", apply("erode", input, s), s);
  const ImageF reopened = apply("dilate", apply("erode", opened, s), s);
  ASSERT_FALSE(reopened.empty());
  EXPECT_EQ(aq::test::max_abs_diff(opened, reopened), 0.0);
  const ImageF closed = apply("erode", apply("dilate", input, s), s);
  const ImageF reclosed = apply("erode", apply("dilate", closed, s), s);
  ASSERT_FALSE(reclosed.empty());
  EXPECT_EQ(aq::test::max_abs_diff(closed, reclosed), 0.0);
}

// Zero padding would darken the border under erosion and one padding would brighten it under
// dilation; clamp-to-edge keeps a constant image constant.
TEST_P(Morphology, ConstantImageStaysConstantUpToTheBorder) {
  const Setting s = setting();
  const ImageF input = aq::test::constant_image(33, 17, 0.25f, 0.5f, 0.75f, 1.0f);
  for (const char* type : {"erode", "dilate"}) {
    const ImageF out = apply(type, input, s);
    ASSERT_FALSE(out.empty());
    EXPECT_EQ(aq::test::max_abs_diff(out, input), 0.0) << type;
  }
}

TEST_P(Morphology, LuminanceOrderOutputsOnlyColoursOfTheWindow) {
  Setting s = setting();
  s.mode = "luminance";
  const ImageF input = quantized(aq::test::random_image(40, 40, 45));
  const auto footprint = s.footprint == "disc" ? aq::reference::MorphologyFootprint::kDisc
                                               : aq::reference::MorphologyFootprint::kSquare;
  for (const char* type : {"erode", "dilate"}) {
    const ImageF out = apply(type, input, s);
    ASSERT_FALSE(out.empty());
    int foreign = 0;
    for (int y = 0; y < input.height; ++y) {
      for (int x = 0; x < input.width; ++x) {
        bool found = false;
        const int r = s.size / 2;
        for (int dy = -r; dy <= r && !found; ++dy) {
          for (int dx = -r; dx <= r && !found; ++dx) {
            if (!aq::reference::in_footprint(dx, dy, s.size, footprint)) continue;
            const int sx = std::clamp(x + dx, 0, input.width - 1);
            const int sy = std::clamp(y + dy, 0, input.height - 1);
            found = true;
            for (int c = 0; c < 4; ++c) found = found && out.at(x, y, c) == input.at(sx, sy, c);
          }
        }
        foreign += !found;
      }
    }
    EXPECT_EQ(foreign, 0) << type;
  }
}

INSTANTIATE_TEST_SUITE_P(Sweep, Morphology,
                         ::testing::Combine(::testing::Values(3, 7),
                                            ::testing::Values("square", "disc"),
                                            ::testing::Values("channel", "luminance"),
                                            ::testing::Values("float", "half")));

// The left column is dark: erosion spreads it one pixel inwards, and the right border does not
// see it (clamping, not wrapping).
TEST(MorphologyBorders, ClampToEdgeNotWrap) {
  ImageF input = aq::test::constant_image(16, 8, 1.0f, 1.0f, 1.0f, 1.0f);
  for (int y = 0; y < input.height; ++y) {
    for (int c = 0; c < 3; ++c) input.at(0, y, c) = 0.0f;
  }
  const ImageF out = apply("erode", input, {3, "square", "channel", "float"});
  ASSERT_FALSE(out.empty());
  for (int y = 0; y < input.height; ++y) {
    EXPECT_EQ(out.at(0, y, 0), 0.0f);
    EXPECT_EQ(out.at(1, y, 0), 0.0f);
    EXPECT_EQ(out.at(2, y, 0), 1.0f);
    EXPECT_EQ(out.at(15, y, 0), 1.0f);
  }
}

// Red beside green: the per-channel minimum is black, a colour found nowhere in the input; the
// luminance order keeps red (the darker of the two).
TEST(MorphologyOrders, PerChannelInventsColoursLuminanceDoesNot) {
  ImageF input(2, 1, 4, 1.0f);
  input.at(0, 0, 0) = 1.0f, input.at(0, 0, 1) = 0.0f, input.at(0, 0, 2) = 0.0f;
  input.at(1, 0, 0) = 0.0f, input.at(1, 0, 1) = 1.0f, input.at(1, 0, 2) = 0.0f;
  const ImageF channel = apply("erode", input, {3, "square", "channel", "float"});
  const ImageF lum = apply("erode", input, {3, "square", "luminance", "float"});
  ASSERT_FALSE(channel.empty());
  ASSERT_FALSE(lum.empty());
  for (int x = 0; x < 2; ++x) {
    EXPECT_EQ(channel.at(x, 0, 0), 0.0f);
    EXPECT_EQ(channel.at(x, 0, 1), 0.0f);
    EXPECT_EQ(lum.at(x, 0, 0), 1.0f);
    EXPECT_EQ(lum.at(x, 0, 1), 0.0f);
  }
}

}  // namespace
