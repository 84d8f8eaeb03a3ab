// Issue 39 in the real window under Xvfb (scripted mode): the widgets around the canvas, driven
// by scripted mouse gestures aimed at them by name (item_rects.h) and played as real input:
// the canvas/viewer split bar, File > Open Recent, a file dropped on the window (through the
// drop callback GLFW has registered), the viewer's histogram checkbox and plot, and the
// parameter slider's tooltip while dragging.
#include <gtest/gtest.h>

#include <aquarelle/core/image.h>
#include <aquarelle/core/image_io.h>

#include <nlohmann/json.hpp>

#include <filesystem>
#include <fstream>
#include <string>

#include "support/harness.h"
#include "window_fixture.h"

namespace {

namespace fs = std::filesystem;
using aq::test::EditorWindowTest;
using aq::test::read_json;

// 16x8 grey EXR: left half 0.125, right half 0.875 (exact in half floats), one pixel 0.5.
void write_two_greys(const fs::path& path) {
  aq::ImageF image(16, 8, 4, 1.0f);
  for (int y = 0; y < 8; ++y) {
    for (int x = 0; x < 16; ++x) {
      const float grey = x == 3 && y == 2 ? 0.5f : (x < 8 ? 0.125f : 0.875f);
      float* pixel = &image.pixels[(static_cast<size_t>(y) * 16 + x) * 4];
      pixel[0] = pixel[1] = pixel[2] = grey;
    }
  }
  ASSERT_TRUE(aq::write_image(path.string(), image).ok());
}

class WidgetWindowTest : public EditorWindowTest {
 protected:
  void use_graph(const std::string& shipped) {
    fs::copy_file(aq::test::source_path(shipped), dir_ / "graph.json");
  }
};

TEST_F(WidgetWindowTest, DraggingTheSplitBarResizesThePanes) {
  use_graph("graphs/tint.json");
  // 1280 wide: 1264 inside the window's padding, 1258 beside the 6-pixel bar. The canvas starts
  // at 0.56 of it; 200 pixels right is 0.56 + 200/1258 = 0.719; far left stops at 0.15.
  std::string log;
  ASSERT_EQ(run_script({{{"do", "wait"}, {"frames", 2}},
                        {{"do", "expect_view"}, {"split", 0.56}, {"tolerance", 0.001}},
                        {{"do", "drag"}, {"item", "##split"}, {"by", {200, 0}}},
                        {{"do", "expect_view"}, {"split", 0.719}, {"tolerance", 0.004}},
                        {{"do", "drag"}, {"item", "##split"}, {"by", {-2000, 0}}},
                        {{"do", "expect_view"}, {"split", 0.15}, {"tolerance", 0.0001}},
                        {{"do", "drag"}, {"item", "##split"}, {"by", {300, 0}}, {"steps", 5}}},
                       &log),
            0)
      << log;
  // The last drag is left on screen: the screenshot shows the wider canvas.
  EXPECT_NE(log.find("canvas share 0.719"), std::string::npos) << log;
  EXPECT_TRUE(fs::exists(dir_ / "shot.png"));
}

TEST_F(WidgetWindowTest, OpenRecentListsOpenedGraphsAndOpensTheOneClicked) {
  use_graph("graphs/tint.json");
  fs::copy_file(aq::test::source_path("graphs/vignette.json"), dir_ / "other.json");
  const std::string first = fs::absolute(dir_ / "graph.json").string();
  std::string log;
  ASSERT_EQ(
      run_script({{{"do", "wait"}, {"frames", 2}},
                  {{"do", "open"}, {"path", "other.json"}},
                  {{"do", "wait"}, {"frames", 2}},
                  {{"do", "expect_view"}, {"document", "other.json"}},
                  // The menu as a user works it: File, then Open Recent, then the first graph.
                  {{"do", "click"}, {"items", {"File", "Open Recent", first}}},
                  {{"do", "wait"}, {"frames", 3}},
                  {{"do", "expect_view"}, {"document", "graph.json"}}},
                 &log),
      0)
      << log;
  EXPECT_NE(log.find("(click): opened " + first), std::string::npos) << log;
}

TEST_F(WidgetWindowTest, OpenRecentIsRefusedForAGraphNeverOpened) {
  use_graph("graphs/tint.json");
  std::string log;
  // Only graph.json was opened: the menu has no other.json, so the click cannot land.
  EXPECT_EQ(
      run_script({{{"do", "click"},
                   {"items", {"File", "Open Recent", fs::absolute(dir_ / "other.json").string()}},
                   {"expect", "refused"}}},
                 &log),
      0)
      << log;
  EXPECT_NE(log.find("is not on screen"), std::string::npos) << log;
}

TEST_F(WidgetWindowTest, AnImageFileDroppedOnTheWindowBecomesAReadNode) {
  use_graph("graphs/tint.json");
  write_two_greys(dir_ / "greys.exr");
  std::string log;
  ASSERT_EQ(run_script({{{"do", "drop"},
                         {"paths", nlohmann::json::array({(dir_ / "greys.exr").string()})}},
                        {{"do", "wait"}, {"frames", 2}},
                        {{"do", "save"}}},
                       &log),
            0)
      << log;
  const nlohmann::json saved = read_json(dir_ / "graph.json");
  int reads = 0;
  for (const auto& [id, node] : saved["nodes"].items()) {
    if (node.value("type", "") != "read") continue;
    ++reads;
    EXPECT_EQ(node["params"]["path"], "greys.exr") << "relative to the graph's folder";
  }
  EXPECT_EQ(reads, 1) << saved.dump(2);
}

TEST_F(WidgetWindowTest, TheHistogramCheckboxShowsThePlotWithTheImagesMinAndMax) {
  write_two_greys(dir_ / "greys.exr");
  std::ofstream(dir_ / "graph.json") << R"({
  "aquarelle": 1,
  "settings": { "width": 16, "height": 8, "fps": 24, "frames": [1, 1] },
  "nodes": { "greys": { "type": "read", "params": { "path": "greys.exr" } } },
  "output": "greys.image"
})";
  std::string log;
  ASSERT_EQ(run_script({{{"do", "play"}, {"frames", 1}},  // until the image is on screen
                        {{"do", "expect_view"}, {"histogram", false}},
                        {{"do", "click"}, {"item", "viewer:histogram"}},
                        {{"do", "wait"}, {"frames", 3}},
                        {{"do", "expect_view"}, {"histogram", true}}},
                       &log),
            0)
      << log;
  // Grey pixels: luminance is the grey; 63 at 0.125, 64 at 0.875, one at 0.5.
  EXPECT_NE(log.find("histogram drawn: min 0.125 max 0.875 over 128 pixels"), std::string::npos)
      << log;
}

TEST_F(WidgetWindowTest, ASlidersTooltipShowsOnHoverButNeverWhileDragging) {
  use_graph("graphs/tint.json");
  std::string log;
  ASSERT_EQ(
      run_script({{{"do", "select"}, {"nodes", nlohmann::json::array({"tint"})}},
                  {{"do", "wait"}, {"frames", 2}},
                  {{"do", "hover"}, {"item", "param:amount"}, {"frames", 8}},
                  {{"do", "expect_view"}, {"tooltips", {{"min_hovering", 4}, {"dragging", 0}}}},
                  {{"do", "drag"}, {"item", "param:amount"}, {"by", {-30, 0}}, {"hold", 6}},
                  {{"do", "expect_view"}, {"tooltips", {{"dragging", 0}, {"min_drag_frames", 12}}}},
                  {{"do", "save"}}},
                 &log),
      0)
      << log;
  const double amount = read_json(dir_ / "graph.json")["nodes"]["tint"]["params"]["amount"];
  EXPECT_LT(amount, 0.75) << "the drag moved the slider left";
}

}  // namespace
