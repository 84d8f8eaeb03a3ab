// graphs/watercolor.json end to end at a small size: it loads, renders finite values in range,
// and the watercolor chain visibly changes the cel-lit image it starts from.
#include <gtest/gtest.h>

#include "support/harness.h"

TEST(WatercolorGraph, RendersAndChangesTheLitImage) {
  aq::test::RenderOptions options;
  options.width = 160;
  options.height = 90;
  options.precision = "half";
  auto watercolor =
      aq::test::render_graph_file(aq::test::source_path("graphs/watercolor.json"), options);
  ASSERT_TRUE(watercolor.ok()) << watercolor.message();
  EXPECT_TRUE(aq::test::all_finite(*watercolor));
  options.output = "light.image";
  auto lit = aq::test::render_graph_file(aq::test::source_path("graphs/watercolor.json"), options);
  ASSERT_TRUE(lit.ok()) << lit.message();
  EXPECT_GT(aq::test::mean_abs_diff(*watercolor, *lit, 3), 0.005);
  EXPECT_LT(aq::test::psnr(*watercolor, *lit, 1.0, 3), 35.0);
}
