// The real editor window under Xvfb, in scripted mode: open a copy of graphs/underwater.json
// (graphs/tint.json while the flagship graph is not in the tree), run edits through the same
// actions the mouse uses, and as mouse gestures played on the canvas (add, link by dragging,
// refused links, parameter changes, drag a node, undo, redo, click an output to view it, zoom,
// save), then check the saved graph and the screenshot.
#include <aquarelle/core/color.h>
#include <aquarelle/core/image_io.h>
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>
#include <string>

#include <unistd.h>

#include "support/harness.h"
#include "window_fixture.h"

namespace {

namespace fs = std::filesystem;

constexpr int kWidth = 1024;
constexpr int kHeight = 640;

// The first node of `type` in the graph, or "".
std::string node_of_type(const nlohmann::json& graph, const std::string& type) {
  for (const auto& [id, node] : graph["nodes"].items()) {
    if (node.value("type", "") == type) return id;
  }
  return "";
}

using aq::test::EditorWindowTest;
using aq::test::read_json;

TEST_F(EditorWindowTest, ScriptedEditsSaveAndScreenshot) {
  fs::path source = aq::test::source_path("graphs/underwater.json");
  if (!fs::exists(source)) source = aq::test::source_path("graphs/tint.json");
  ASSERT_TRUE(fs::exists(source)) << source;
  const fs::path graph_path = dir_ / "graph.json";
  fs::copy_file(source, graph_path);
  const nlohmann::json original = read_json(graph_path);
  const std::string output = original["output"].get<std::string>();
  const std::string scene = node_of_type(original, "scene");
  const std::string gbuffer = node_of_type(original, "gbuffer");
  ASSERT_FALSE(scene.empty()) << "the test graph needs a scene node";
  ASSERT_FALSE(gbuffer.empty()) << "the test graph needs a gbuffer node";

  const std::string output_node = output.substr(0, output.find('.'));
  // Mouse actions ("drag_link", "drag_node", "click_output", "wheel") play as real input on the
  // canvas; the others call the same actions the mouse handlers call.
  nlohmann::json script = {
      {"actions",
       {
           {{"do", "add_node"}, {"type", "blur"}, {"id", "soft"}, {"at", {950, -300}}},
           {{"do", "fit"}, {"whole", true}},  // every port on screen for the gestures
           {{"do", "drag_link"}, {"from", output}, {"to", "soft.image"}},
           {{"do", "drag_link"},
            {"from", scene + ".scene"},
            {"to", "soft.image"},
            {"expect", "refused"}},
           {{"do", "drag_link"},
            {"from", "soft.image"},
            {"to", output_node + ".image"},
            {"expect", "refused"}},
           {{"do", "set_param"}, {"node", "soft"}, {"param", "sigma"}, {"value", 2.5}},
           {{"do", "set_param"},
            {"node", "soft"},
            {"param", "sigma"},
            {"value", -1.0},
            {"expect", "refused"}},
           {{"do", "drag_node"}, {"node", "soft"}, {"by", {60, 30}}},
           {{"do", "undo"}},
           {{"do", "move"}, {"node", "soft"}, {"to", {950, -260}}},
           {{"do", "add_node"}, {"type", "vignette"}, {"id", "extra"}},
           {{"do", "undo"}},
           {{"do", "redo"}},
           {{"do", "undo"}},
           {{"do", "link"}, {"from", gbuffer + ".depth"}, {"to", "soft.depth"}},
           {{"do", "set_output"}, {"output", "soft.image"}},
           {{"do", "select"}, {"nodes", {"soft"}}},
           {{"do", "click_output"}, {"output", gbuffer + ".depth"}},
           {{"do", "wheel"}, {"steps", 1}},
           {{"do", "save"}},
       }}};
  std::ofstream(dir_ / "script.json") << script.dump(2);

  std::string log;
  int status = run_editor("graph.json --script script.json --screenshot shot.png --quit --size " +
                              std::to_string(kWidth) + "x" + std::to_string(kHeight),
                          &log);
  ASSERT_EQ(status, 0) << log;
  EXPECT_NE(log.find("refused as expected: cannot link " + scene + ".scene"), std::string::npos)
      << log;
  EXPECT_NE(log.find("cycle"), std::string::npos) << log;
  EXPECT_NE(log.find("(drag_node): moved soft to"), std::string::npos) << log;
  EXPECT_NE(log.find("(click_output): viewing " + gbuffer + ".depth"), std::string::npos) << log;

  // The saved graph: the new node, its links and parameter, its position; the undone node gone;
  // every original id kept.
  nlohmann::json saved = read_json(graph_path);
  ASSERT_TRUE(saved["nodes"].contains("soft")) << saved.dump(2);
  EXPECT_EQ(saved["nodes"]["soft"]["type"], "blur");
  EXPECT_EQ(saved["nodes"]["soft"]["inputs"]["image"], output);
  EXPECT_EQ(saved["nodes"]["soft"]["inputs"]["depth"], gbuffer + ".depth");
  EXPECT_DOUBLE_EQ(saved["nodes"]["soft"]["params"]["sigma"].get<double>(), 2.5);
  EXPECT_FALSE(saved["nodes"].contains("extra"));
  EXPECT_EQ(saved["output"], "soft.image");
  EXPECT_EQ(saved["editor"]["positions"]["soft"], nlohmann::json::array({950, -260}));
  for (const auto& [id, node] : original["nodes"].items()) {
    ASSERT_TRUE(saved["nodes"].contains(id)) << id;
    EXPECT_EQ(saved["nodes"][id]["type"], node["type"]) << id;
    EXPECT_TRUE(saved["editor"]["positions"].contains(id)) << "no position saved for " << id;
  }
  EXPECT_FALSE(fs::exists(dir_ / "graph.autosave.json"));

  // The screenshot: the window's size, and a real picture (canvas, nodes, the viewed depth).
  auto config = aq::ColorConfig::load();
  ASSERT_TRUE(config.ok()) << config.message();
  auto shot = aq::read_image((dir_ / "shot.png").string(), *config);
  ASSERT_TRUE(shot.ok()) << shot.message();
  EXPECT_EQ(shot->width, kWidth);
  EXPECT_EQ(shot->height, kHeight);
  std::set<uint32_t> colours;
  for (size_t i = 0; i + 3 < shot->pixels.size(); i += 4) {
    auto q = [&](int c) { return static_cast<uint32_t>(shot->pixels[i + c] * 255.0f + 0.5f); };
    colours.insert(q(0) << 16 | q(1) << 8 | q(2));
  }
  EXPECT_GT(colours.size(), 50u) << "the screenshot looks blank";
}

TEST_F(EditorWindowTest, UnexpectedRefusalFailsTheScript) {
  fs::copy_file(aq::test::source_path("graphs/tint.json"), dir_ / "graph.json");
  std::ofstream(dir_ / "script.json")
      << R"([{"do": "link", "from": "scene.scene", "to": "tint.image"}])";
  std::string log;
  EXPECT_EQ(run_editor("graph.json --script script.json --quit --size 320x240", &log), 1) << log;
  EXPECT_NE(log.find("incompatible port types"), std::string::npos) << log;
  // Nothing was saved: the file is unchanged.
  EXPECT_EQ(read_json(dir_ / "graph.json"), read_json(aq::test::source_path("graphs/tint.json")));
}

TEST_F(EditorWindowTest, UnknownActionIsAnError) {
  std::ofstream(dir_ / "script.json") << R"([{"do": "fly"}])";
  std::string log;
  EXPECT_EQ(run_editor("new.json --script script.json --quit --size 320x240", &log), 1) << log;
  EXPECT_NE(log.find("unknown action 'fly'"), std::string::npos) << log;
  EXPECT_FALSE(fs::exists(dir_ / "new.json"));
}

// Issue 16: the flagship graph plays while the UI keeps drawing. Evaluation runs on a worker
// thread; the scripted mode prints how many UI frames were drawn while an evaluation was in
// flight. No timing is asserted (speed is reported, docs/editor.md), only that frames were drawn.
TEST_F(EditorWindowTest, UiKeepsDrawingWhileTheFlagshipGraphPlays) {
  fs::path source = aq::test::source_path("graphs/underwater.json");
  if (!fs::exists(source)) source = aq::test::source_path("graphs/watercolor.json");
  fs::copy_file(source, dir_ / "graph.json");
  std::ofstream(dir_ / "script.json") << R"([{"do": "play", "frames": 3}])";
  std::string log;
  ASSERT_EQ(run_editor("graph.json --script script.json --quit --size 1280x720", &log), 0) << log;
  // Playback keeps the graph's pace and drops frames it cannot show in time (as Nuke's and
  // Blender's do), so on a loaded machine the clock may have moved past frame 4 by the time it is
  // on screen: at least three frames on from the first.
  const size_t played = log.find("(play): played to frame ");
  ASSERT_NE(played, std::string::npos) << log;
  int reached = 0;
  ASSERT_EQ(std::sscanf(log.c_str() + played, "(play): played to frame %d", &reached), 1) << log;
  EXPECT_GE(reached, 4) << log;
  const size_t at = log.find("UI frames: ");
  ASSERT_NE(at, std::string::npos) << log;
  int frames = 0;
  int while_evaluating = 0;
  ASSERT_EQ(std::sscanf(log.c_str() + at, "UI frames: %d (%d while evaluating)", &frames,
                        &while_evaluating),
            2)
      << log;
  std::printf("%s\n", log.substr(at, log.find('\n', at) - at).c_str());  // for docs/editor.md
  EXPECT_GE(while_evaluating, 3) << "the UI drew no frames while the graph evaluated: " << log;
  EXPECT_FALSE(fs::exists(dir_ / "graph.autosave.json"));
  // Playing is not an edit: the file is untouched.
  EXPECT_EQ(read_json(dir_ / "graph.json"), read_json(source));
}

// Issue 16: fast key chords are not lost, Save As asks before replacing, an unedited save keeps
// the bytes, and the Nuke-style edits (insert, rename, bypass, copy and paste) from a script.
TEST_F(EditorWindowTest, ChordsSaveSafelyAndNukeStyleEdits) {
  const fs::path source = aq::test::source_path("graphs/tint.json");
  fs::copy_file(source, dir_ / "graph.json");
  std::ofstream(dir_ / "other.json") << "{\"aquarelle\": 1, \"nodes\": {}}\n";
  nlohmann::json script = {
      {{"do", "key"}, {"chord", "ctrl+s"}},  // pressed and released between two frames
      {{"do", "save"}, {"path", "other.json"}, {"expect", "refused"}},
      {{"do", "insert"}, {"type", "blur"}, {"after", "tint.image"}, {"at", {900, 60}}},
      {{"do", "rename"}, {"node", "blur"}, {"to", "soft"}},
      {{"do", "bypass"}, {"nodes", {"soft"}}},
      {{"do", "select"}, {"nodes", {"soft"}}},
      {{"do", "copy"}},
      {{"do", "paste"}, {"at", {900, 300}}},
      {{"do", "save"}, {"path", "edited.json"}},
  };
  std::string log;
  ASSERT_EQ(run_script(script, &log), 0) << log;
  EXPECT_NE(log.find("(key): done"), std::string::npos) << log;
  EXPECT_NE(log.find("exists already"), std::string::npos) << log;
  std::ifstream original(source, std::ios::binary), saved(dir_ / "graph.json", std::ios::binary);
  std::stringstream a, b;
  a << original.rdbuf();
  b << saved.rdbuf();
  EXPECT_EQ(b.str(), a.str()) << "ctrl+s of an unedited graph: the same bytes";
  EXPECT_EQ(read_json(dir_ / "other.json"),
            nlohmann::json::parse("{\"aquarelle\": 1, \"nodes\": {}}"));
  nlohmann::json edited = read_json(dir_ / "edited.json");
  EXPECT_EQ(edited["nodes"]["soft"]["inputs"]["image"], "tint.image") << edited.dump(2);
  EXPECT_EQ(edited["output"], "soft.image");
  EXPECT_EQ(edited["nodes"]["soft"]["bypass"], true) << "on the node: the render honours it";
  ASSERT_TRUE(edited["nodes"].contains("blur2")) << "the pasted copy: " << edited.dump(2);
  EXPECT_EQ(edited["nodes"]["blur2"]["inputs"]["image"], "tint.image");
  EXPECT_EQ(edited["editor"]["positions"]["blur2"], nlohmann::json::array({900, 300}));
}

TEST_F(EditorWindowTest, GroupCollapsesNodesLinksAtItsPortsAndUngroups) {
  fs::copy_file(aq::test::source_path("graphs/tint.json"), dir_ / "graph.json");
  nlohmann::json script = {
      {{"do", "select"}, {"nodes", {"gbuf", "light"}}},
      {{"do", "key"}, {"chord", "ctrl+g"}},
      {{"do", "add_node"}, {"type", "blur"}, {"at", {700, 420}}},
      {{"do", "fit"}},
      // A link dragged from the collapsed group's port reaches the inner node.
      {{"do", "drag_link"}, {"from", "light.image"}, {"to", "blur.image"}},
      {{"do", "drag_node"}, {"node", "group.Group"}, {"by", {0, 60}}},
      {{"do", "save"}, {"path", "grouped.json"}},
      {{"do", "select"}, {"nodes", {"group.Group"}}},
      {{"do", "key"}, {"chord", "ctrl+alt+g"}},
      {{"do", "save"}, {"path", "ungrouped.json"}},
      {{"do", "undo"}},
      {{"do", "select"}, {"nodes", {"tint"}}},
  };
  std::string log;
  ASSERT_EQ(run_script(script, &log), 0) << log;
  const nlohmann::json grouped = read_json(dir_ / "grouped.json");
  const nlohmann::json groups = grouped["editor"]["groups"];
  ASSERT_EQ(groups.size(), 1u) << grouped.dump(2);
  EXPECT_EQ(groups[0]["name"], "Group");
  EXPECT_EQ(groups[0]["nodes"], nlohmann::json::array({"gbuf", "light"}));
  EXPECT_EQ(groups[0]["collapsed"], true);
  EXPECT_EQ(grouped["nodes"]["blur"]["inputs"]["image"], "light.image") << grouped.dump(2);
  // The group sits at its nodes' top-left, before and after the drag: they moved with it.
  const auto& positions = grouped["editor"]["positions"];
  for (int axis : {0, 1}) {
    EXPECT_DOUBLE_EQ(
        groups[0]["position"][axis].get<double>(),
        std::min(positions["gbuf"][axis].get<double>(), positions["light"][axis].get<double>()))
        << grouped.dump(2);
  }
  EXPECT_GT(groups[0]["position"][1].get<double>(), 0.0) << "dragged down";
  const nlohmann::json ungrouped = read_json(dir_ / "ungrouped.json");
  EXPECT_FALSE(ungrouped["editor"].contains("groups")) << ungrouped.dump(2);
  EXPECT_EQ(ungrouped["editor"]["positions"]["light"], positions["light"]);
  // The screenshot shows the group again (the ungroup was undone) beside the new blur.
  auto config = aq::ColorConfig::load();
  ASSERT_TRUE(config.ok());
  auto shot = aq::read_image((dir_ / "shot.png").string(), *config);
  ASSERT_TRUE(shot.ok()) << shot.message();
  EXPECT_EQ(shot->width, 1280);
}

// A/B wipe of two outputs: A (the viewed tint.image, the lit underwater picture) left of the
// line, B (gbuf.albedo, black where nothing was drawn: the water above the sea floor) right.
TEST_F(EditorWindowTest, WipeComparesTwoOutputs) {
  fs::copy_file(aq::test::source_path("graphs/tint.json"), dir_ / "graph.json");
  nlohmann::json script = {
      {{"do", "compare"}, {"output", "gbuf.albedo"}},
      {{"do", "view"}, {"wipe", 0.3}},
      {{"do", "compare"}, {"output", "nosuch.image"}, {"expect", "refused"}},
  };
  std::string log;
  ASSERT_EQ(run_script(script, &log), 0) << log;
  EXPECT_NE(log.find("compare A tint.image | B gbuf.albedo"), std::string::npos) << log;
  auto config = aq::ColorConfig::load();
  ASSERT_TRUE(config.ok());
  auto shot = aq::read_image((dir_ / "shot.png").string(), *config);
  ASSERT_TRUE(shot.ok()) << shot.message();
  ASSERT_EQ(shot->width, 1280);
  // The viewer's picture spans x 741..1253 at this window size, the water at its top (y 100
  // from the top, PNG rows read bottom-up). Left of the line (30 %): A's water, blue-green.
  const int row = shot->height - 1 - 100;
  EXPECT_GT(shot->at(780, row, 2), 0.1f) << "A: the tinted water";
  for (int c = 0; c < 3; ++c) {
    EXPECT_LT(shot->at(1200, row, c), 0.02f) << "B: albedo is black where nothing was drawn";
  }
}

}  // namespace