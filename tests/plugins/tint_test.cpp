// Headless tests of the `tint` node against the CPU reference (reference/tint.h): float
// and half precision, amount 0 and 1 exact, alpha kept, a parameter sweep.
#include <gtest/gtest.h>

#include "aquarelle/reference/tint.h"
#include "support/harness.h"

namespace {

using aq::ImageF;
using aq::reference::TintParams;

aq::Result<ImageF> run(const ImageF& image, const TintParams& p, const char* precision = "float") {
  aq::test::RenderOptions options;
  options.precision = precision;
  return aq::test::run_node("tint", {{"image", image}},
                            {{"amount", p.amount}, {"tint", {p.tint[0], p.tint[1], p.tint[2]}}},
                            options);
}

TEST(Tint, MatchesReferenceWithDefaults) {
  const ImageF image = aq::test::random_image(64, 40, 41, 0.0f, 4.0f);
  const ImageF expected = aq::reference::tint(image);
  auto got = run(image, {});
  ASSERT_TRUE(got.ok()) << got.message();
  EXPECT_LE(aq::test::max_abs_diff(*got, expected), 2e-6 * 4);
  auto half = run(image, {}, "half");
  ASSERT_TRUE(half.ok()) << half.message();
  // Outputs reach 1.07; RGBA16F keeps 11 significant bits and llvmpipe's conversion may be off
  // by one unit in the last place: 2^-10 in [1, 2).
  EXPECT_LE(aq::test::max_abs_diff(*half, expected), 1.0e-3);
  std::printf("[tint] float max abs %.3g, half max abs %.3g\n",
              aq::test::max_abs_diff(*got, expected), aq::test::max_abs_diff(*half, expected));
}

TEST(Tint, AmountZeroIsExactIdentity) {
  const ImageF image = aq::test::random_image(31, 9, 42, -2.0f, 5.0f);
  auto got = run(image, {0.0, {0.3, 0.2, 0.1}});
  ASSERT_TRUE(got.ok()) << got.message();
  EXPECT_EQ(aq::test::max_abs_diff(*got, image), 0.0);
}

TEST(Tint, AmountOneIsExactlyTheTintWithAlphaKept) {
  ImageF image = aq::test::random_image(16, 16, 43);
  for (int y = 0; y < 16; ++y)
    for (int x = 0; x < 16; ++x) image.at(x, y, 3) = 0.25f + 0.5f * (x % 2);
  const TintParams params{1.0, {0.0, 0.07, 0.1}};
  auto got = run(image, params);
  ASSERT_TRUE(got.ok()) << got.message();
  for (int y = 0; y < 16; ++y)
    for (int x = 0; x < 16; ++x) {
      for (int c = 0; c < 3; ++c) EXPECT_EQ(got->at(x, y, c), static_cast<float>(params.tint[c]));
      EXPECT_EQ(got->at(x, y, 3), image.at(x, y, 3));
    }
}

TEST(Tint, ParameterSweepMatchesReference) {
  const ImageF image = aq::test::random_image(32, 32, 44);
  for (double amount : {0.05, 0.2, 0.5, 0.75, 0.99}) {
    for (auto colour : {std::array<double, 3>{0.0, 0.07, 0.1}, std::array<double, 3>{1, 0.5, 0}}) {
      const TintParams params{amount, colour};
      auto got = run(image, params);
      ASSERT_TRUE(got.ok()) << got.message();
      EXPECT_LE(aq::test::max_abs_diff(*got, aq::reference::tint(image, params)), 2e-6)
          << "amount " << amount;
    }
  }
}

}  // namespace
