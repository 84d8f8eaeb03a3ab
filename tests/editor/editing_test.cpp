// Nuke-style editing without a window: clipboard copy and paste as graph JSON, insert after a
// node and onto a link, rename (links and output follow), bypass (evaluation wires around the
// node), auto-layout, non-overlapping placement of new and duplicated nodes, the status line
// after a deselect; and the viewer's policies: layout is not part of the evaluation key, drafts
// only when the full evaluation cannot keep up; the UI frame-time summary; the file chooser's
// listing.
#include "editor/canvas_view.h"
#include "editor/document.h"
#include "editor/editor_actions.h"
#include "editor/eval_policy.h"
#include "editor/fake_node_types.h"
#include "editor/file_dialog.h"
#include "editor/frame_stats.h"
#include "editor/image_view.h"

#include <aquarelle/core/bypass.h>

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

namespace aq::editor {
namespace {

namespace fs = std::filesystem;

const Registry& registry() {
  return test::fake_registry();
}

// src → a → b (output b.image)
class EditingTest : public ::testing::Test {
 protected:
  void SetUp() override {
    ASSERT_TRUE(doc.add_node("source", {0, 0}, "src").ok());
    ASSERT_TRUE(doc.add_node("filter", {250, 0}, "a").ok());
    ASSERT_TRUE(doc.add_node("filter", {500, 0}, "b").ok());
    ASSERT_TRUE(doc.link({"src", "image"}, "a", "image"));
    ASSERT_TRUE(doc.link({"a", "image"}, "b", "image"));
    ASSERT_TRUE(doc.set_output(PortRef{"b", "image"}));
  }
  Document doc{registry()};
  EditorState state{doc};
};

TEST_F(EditingTest, CopyAndPasteThroughGraphJson) {
  ASSERT_TRUE(doc.set_param("a", "amount", 2.5));
  actions::select(state, {"a", "b"});
  const std::string text = actions::copy_selection(state);
  auto json = nlohmann::json::parse(text);
  EXPECT_EQ(json["nodes"]["a"]["params"]["amount"], 2.5);
  EXPECT_EQ(json["nodes"]["b"]["inputs"]["image"], "a.image");
  EXPECT_EQ(json["editor"]["positions"]["b"], nlohmann::json::array({500, 0}));

  // Into this graph: fresh ids, the inner link follows, the link from outside stays.
  ASSERT_TRUE(actions::paste(state, text, Position{100, 300}));
  EXPECT_EQ(state.selection, (std::set<std::string>{"filter2", "filter3"}));
  const Graph& graph = doc.graph();
  EXPECT_EQ(graph.nodes.at("filter2").inputs.at("image"), (PortRef{"src", "image"}));
  EXPECT_EQ(graph.nodes.at("filter3").inputs.at("image"), (PortRef{"filter2", "image"}));
  EXPECT_EQ(graph.nodes.at("filter2").params.at("amount"), 2.5);
  EXPECT_EQ(doc.position("filter2"), (Position{100, 300}));
  EXPECT_EQ(doc.position("filter3"), (Position{350, 300}));
  ASSERT_TRUE(doc.undo());  // one step
  EXPECT_EQ(doc.graph().nodes.size(), 3u);

  // Into another graph: the link to a node it lacks is dropped, ids kept when free.
  Document other(registry());
  EditorState other_state(other);
  ASSERT_TRUE(actions::paste(other_state, text, std::nullopt));
  EXPECT_TRUE(other.graph().nodes.at("a").inputs.empty());
  EXPECT_EQ(other.graph().nodes.at("b").inputs.at("image"), (PortRef{"a", "image"}));
  EXPECT_FALSE(actions::paste(other_state, "not json", std::nullopt).ok());
  EXPECT_NE(other_state.status.find("nothing to paste"), std::string::npos) << other_state.status;
}

TEST_F(EditingTest, InsertAfterTheSelectedNodeMovesItsReaders) {
  actions::select(state, {"a"});
  auto inserted = actions::add_node_at_cursor(state, "filter", {250, 0});
  ASSERT_TRUE(inserted.ok());
  const Graph& graph = doc.graph();
  EXPECT_EQ(graph.nodes.at(*inserted).inputs.at("image"), (PortRef{"a", "image"}));
  EXPECT_EQ(graph.nodes.at("b").inputs.at("image"), (PortRef{*inserted, "image"}));
  // Asked for a's own spot: moved clear of it.
  Rect placed = node_rect(graph, registry(), *inserted);
  for (const char* id : {"src", "a", "b"}) {
    EXPECT_FALSE(placed.overlaps(node_rect(graph, registry(), id))) << id;
  }
  ASSERT_TRUE(doc.undo());  // one step
  EXPECT_EQ(doc.graph().nodes.at("b").inputs.at("image"), (PortRef{"a", "image"}));
  EXPECT_FALSE(doc.graph().nodes.count(*inserted));
}

TEST_F(EditingTest, InsertOnALinkSplicesOnlyThatLink) {
  ASSERT_TRUE(doc.link({"src", "image"}, "b", "mask"));
  auto inserted = doc.insert_node_on_link("filter", {375, 200}, "b", "mask");
  ASSERT_TRUE(inserted.ok()) << inserted.message();
  const Graph& graph = doc.graph();
  EXPECT_EQ(graph.nodes.at(*inserted).inputs.at("image"), (PortRef{"src", "image"}));
  EXPECT_EQ(graph.nodes.at("b").inputs.at("mask"), (PortRef{*inserted, "image"}));
  EXPECT_EQ(graph.nodes.at("a").inputs.at("image"), (PortRef{"src", "image"}))
      << "the other reader of src keeps its link";
  EXPECT_FALSE(doc.insert_node_on_link("filter", {0, 0}, "src", "image").ok());
}

TEST_F(EditingTest, AnUnlinkedNodeDroppedOnALinkIsSplicedIn) {
  ASSERT_TRUE(doc.add_node("filter", {375, 200}, "loose").ok());
  ASSERT_TRUE(doc.splice_into_link("loose", "b", "image"));
  EXPECT_EQ(doc.graph().nodes.at("loose").inputs.at("image"), (PortRef{"a", "image"}));
  EXPECT_EQ(doc.graph().nodes.at("b").inputs.at("image"), (PortRef{"loose", "image"}));
  EXPECT_FALSE(doc.splice_into_link("loose", "b", "image").ok()) << "already on it";
  ASSERT_TRUE(doc.undo());
  EXPECT_EQ(doc.graph().nodes.at("b").inputs.at("image"), (PortRef{"a", "image"}));
}

TEST_F(EditingTest, LinksOnTheCanvasAreHitAlongTheirCurve) {
  CanvasView view;
  auto layouts = layout_graph(doc.graph(), registry(), view, {0, 0});
  const NodeLayout* a = nullptr;
  const NodeLayout* b = nullptr;
  for (const auto& layout : layouts) {
    if (layout.id == "a") a = &layout;
    if (layout.id == "b") b = &layout;
  }
  ASSERT_TRUE(a && b);
  Vec2 middle = link_point(a->outputs[0].at, b->inputs[0].at, view.zoom, 0.5f);
  auto hit = link_at(doc.graph(), layouts, middle, 4.0f, view.zoom);
  ASSERT_TRUE(hit.has_value());
  EXPECT_EQ(hit->node, "b");
  EXPECT_EQ(hit->input, "image");
  EXPECT_FALSE(link_at(doc.graph(), layouts, {middle.x, middle.y + 60}, 4.0f, view.zoom));
}

TEST_F(EditingTest, RenameUpdatesLinksOutputAndPosition) {
  state.viewed = PortRef{"a", "image"};
  ASSERT_TRUE(actions::rename(state, "a", "soften"));
  const Graph& graph = doc.graph();
  EXPECT_FALSE(graph.nodes.count("a"));
  EXPECT_EQ(graph.nodes.at("b").inputs.at("image"), (PortRef{"soften", "image"}));
  EXPECT_EQ(doc.position("soften"), (Position{250, 0}));
  EXPECT_FALSE(doc.position("a"));
  EXPECT_EQ(state.viewed, (PortRef{"soften", "image"}));
  ASSERT_TRUE(actions::rename(state, "b", "final"));
  EXPECT_EQ(doc.graph().output, (PortRef{"final", "image"}));
  EXPECT_FALSE(actions::rename(state, "final", "src").ok()) << "taken";
  EXPECT_FALSE(actions::rename(state, "final", "a.b").ok()) << "no dots in ids";
  ASSERT_TRUE(doc.undo());
  EXPECT_EQ(doc.graph().output, (PortRef{"b", "image"}));
}

TEST_F(EditingTest, BypassWiresEvaluationAroundTheNodeAndIsSaved) {
  actions::select(state, {"a"});
  ASSERT_TRUE(actions::toggle_bypass(state));
  EXPECT_TRUE(doc.bypassed("a"));
  auto evaluated = apply_bypass(doc.graph(), registry());
  ASSERT_TRUE(evaluated.ok()) << evaluated.message();
  EXPECT_EQ(evaluated->nodes.at("b").inputs.at("image"), (PortRef{"src", "image"}));
  EXPECT_EQ(doc.graph().nodes.at("b").inputs.at("image"), (PortRef{"a", "image"}))
      << "the document keeps the link";
  EXPECT_TRUE(doc.graph().nodes.at("a").bypass) << "saved on the node, read by the render";
  EXPECT_EQ(nlohmann::json::parse(doc.text_to_save())["nodes"]["a"]["bypass"], true);
  // A bypassed output node shows its input; a chain of bypassed nodes is followed.
  actions::select(state, {"b"});
  ASSERT_TRUE(actions::toggle_bypass(state));
  EXPECT_EQ(apply_bypass(doc.graph(), registry())->output, (PortRef{"src", "image"}));
  ASSERT_TRUE(doc.undo());
  ASSERT_TRUE(doc.undo());
  EXPECT_FALSE(doc.bypassed("a"));
  EXPECT_FALSE(doc.graph().editor.contains("bypassed"));
  EXPECT_FALSE(nlohmann::json::parse(doc.text_to_save())["nodes"]["a"].contains("bypass"));
}

TEST_F(EditingTest, BackdropsFrameNodesMoveWithThemAndAreSaved) {
  actions::select(state, {"a", "b"});
  ASSERT_TRUE(actions::backdrop_around_selection(state, "smoothing"));
  auto backdrops = read_backdrops(doc.graph());
  ASSERT_EQ(backdrops.size(), 1u);
  EXPECT_EQ(backdrops[0].label, "smoothing");
  for (const char* id : {"a", "b"}) {
    Rect r = node_rect(doc.graph(), registry(), id);
    EXPECT_TRUE(backdrops[0].contains({r.min.x, r.min.y}) &&
                backdrops[0].contains({r.max.x, r.max.y}))
        << id;
  }
  EXPECT_FALSE(backdrops[0].contains(*doc.position("src")));
  // Dragging it (one undo step) carries the nodes on it, not the others.
  ASSERT_TRUE(doc.move_backdrop(0, {10, 5}, "backdrop"));
  ASSERT_TRUE(doc.move_backdrop(0, {10, 5}, "backdrop"));
  doc.end_gesture();
  EXPECT_EQ(doc.position("a"), (Position{270, 10}));
  EXPECT_EQ(doc.position("b"), (Position{520, 10}));
  EXPECT_EQ(doc.position("src"), (Position{0, 0}));
  ASSERT_TRUE(doc.set_backdrop_label(0, "opening"));
  const std::string saved = doc.text_to_save();
  auto json = nlohmann::json::parse(saved);
  EXPECT_EQ(json["editor"]["backdrops"][0]["label"], "opening");
  EXPECT_EQ(json["editor"]["backdrops"][0]["rect"].size(), 4u);
  ASSERT_TRUE(doc.undo());  // label
  ASSERT_TRUE(doc.undo());  // the whole drag
  EXPECT_EQ(doc.position("a"), (Position{250, 0}));
  EXPECT_EQ(read_backdrops(doc.graph())[0].at.x, backdrops[0].at.x);
  ASSERT_TRUE(doc.undo());  // the backdrop
  EXPECT_TRUE(read_backdrops(doc.graph()).empty());
}

TEST_F(EditingTest, RerouteDotsBendALinkAndFollowIt) {
  ASSERT_TRUE(doc.add_reroute("b", "image", {400, 200}));
  ASSERT_TRUE(doc.add_reroute("b", "image", {300, 200}));
  auto dots = read_reroutes(doc.graph(), "b", "image");
  ASSERT_EQ(dots.size(), 2u);
  EXPECT_EQ(dots[0], (Position{300, 200})) << "ordered from the source's side";
  EXPECT_EQ(doc.graph().editor["reroutes"]["b.image"]["from"], "a.image");
  // The curve goes through them: a point on the dot's way is on the link.
  CanvasView view;
  auto layouts = layout_graph(doc.graph(), registry(), view, {0, 0});
  auto through = link_at(doc.graph(), layouts, view.to_screen({0, 0}, {350, 200}), 4.0f, 1.0f);
  ASSERT_TRUE(through.has_value());
  EXPECT_EQ(through->node, "b");
  auto hit = reroute_at(doc.graph(), view, {0, 0}, view.to_screen({0, 0}, {400, 200}), 6.0f);
  ASSERT_TRUE(hit.has_value());
  EXPECT_EQ(hit->index, 1u);
  ASSERT_TRUE(doc.move_reroute("b", "image", 1, {420, 220}, "dot"));
  ASSERT_TRUE(doc.move_reroute("b", "image", 1, {440, 240}, "dot"));
  doc.end_gesture();
  EXPECT_EQ(read_reroutes(doc.graph(), "b", "image")[1], (Position{440, 240}));
  ASSERT_TRUE(doc.undo());  // the whole drag
  EXPECT_EQ(read_reroutes(doc.graph(), "b", "image")[1], (Position{400, 200}));
  // Relinked elsewhere: the old dots no longer apply.
  ASSERT_TRUE(doc.link({"src", "image"}, "b", "image"));
  EXPECT_TRUE(read_reroutes(doc.graph(), "b", "image").empty());
  ASSERT_TRUE(doc.undo());
  ASSERT_TRUE(doc.remove_reroute("b", "image", 0));
  EXPECT_EQ(read_reroutes(doc.graph(), "b", "image").size(), 1u);
}

TEST_F(EditingTest, AutoLayoutIsOneUndoStep) {
  ASSERT_TRUE(doc.move_nodes({{"a", {900, 900}}, {"b", {-400, 30}}}));
  ASSERT_TRUE(actions::auto_layout(state));
  auto automatic = automatic_positions(doc.graph());
  for (const char* id : {"src", "a", "b"}) EXPECT_EQ(doc.position(id), automatic[id]) << id;
  EXPECT_LT(doc.position("src")->x, doc.position("a")->x);
  EXPECT_LT(doc.position("a")->x, doc.position("b")->x);
  ASSERT_TRUE(doc.undo());
  EXPECT_EQ(doc.position("a"), (Position{900, 900}));
}

TEST_F(EditingTest, DuplicatesDoNotCoverTheirOriginals) {
  actions::select(state, {"a", "b"});
  ASSERT_TRUE(actions::duplicate_selection(state));
  ASSERT_EQ(state.selection.size(), 2u);
  for (const auto& copy : state.selection) {
    Rect rect = node_rect(doc.graph(), registry(), copy);
    for (const char* id : {"src", "a", "b"}) {
      EXPECT_FALSE(rect.overlaps(node_rect(doc.graph(), registry(), id))) << copy << " on " << id;
    }
  }
}

TEST_F(EditingTest, TheStatusLineShowsASliderValueAsTyped) {
  ASSERT_TRUE(actions::set_param(state, "a", "amount", static_cast<double>(0.9f), true));
  EXPECT_EQ(state.status, "a.amount = 0.9");
}

TEST_F(EditingTest, DeselectingClearsTheSelectionCountFromTheStatusLine) {
  actions::select(state, {"a"});
  EXPECT_EQ(state.status, "1 node(s) selected");
  actions::clear_selection(state);
  EXPECT_TRUE(state.selection.empty());
  EXPECT_EQ(state.status, "");
  state.status = "saved graph.json";
  actions::clear_selection(state);
  EXPECT_EQ(state.status, "saved graph.json") << "other messages stay";
}

TEST_F(EditingTest, LayoutIsNotPartOfTheEvaluationKey) {
  const auto output = doc.graph().output;
  const uint64_t key = evaluation_key(doc.graph(), output);
  ASSERT_TRUE(doc.move_nodes({{"a", {300, 80}}}));
  EXPECT_EQ(evaluation_key(doc.graph(), output), key) << "moving a node";
  ASSERT_TRUE(doc.add_node("filter", {0, 400}, "loose").ok());
  EXPECT_EQ(evaluation_key(doc.graph(), output), key) << "adding an unconnected node";
  ASSERT_TRUE(doc.set_param("loose", "amount", 3.0));
  EXPECT_EQ(evaluation_key(doc.graph(), output), key) << "editing a node the output ignores";
  ASSERT_TRUE(doc.set_param("a", "amount", 3.0));
  EXPECT_NE(evaluation_key(doc.graph(), output), key) << "editing an upstream node";
  const uint64_t edited = evaluation_key(doc.graph(), output);
  ASSERT_TRUE(doc.link({"loose", "image"}, "b", "mask"));
  EXPECT_NE(evaluation_key(doc.graph(), output), edited) << "linking it in";
  EXPECT_NE(evaluation_key(doc.graph(), PortRef{"a", "image"}),
            evaluation_key(doc.graph(), output));
  EXPECT_EQ(upstream_nodes(doc.graph(), PortRef{"a", "image"}),
            (std::set<std::string>{"src", "a"}));
}

// A graph saved by an older editor kept bypass in editor.bypassed: it opens bypassed, and
// saving moves the mark onto the node (only those lines change).
TEST(BypassMigration, OldEditorMarksOpenBypassedAndSaveOnTheNode) {
  const std::string text = R"({
  "aquarelle": 1,
  "nodes": {
    "src": { "type": "source" },
    "a": { "type": "filter", "inputs": { "image": "src.image" } }
  },
  "output": "a.image",
  "editor": { "bypassed": { "a": true }, "positions": { "src": [0, 0], "a": [250, 0] } }
}
)";
  const fs::path path = fs::temp_directory_path() / "aq_bypass_migration_test.json";
  std::ofstream(path, std::ios::binary) << text;
  Document doc(registry());
  ASSERT_TRUE(doc.open(path.string()));
  EXPECT_TRUE(doc.bypassed("a"));
  const std::string saved = doc.text_to_save();
  EXPECT_NE(saved.find(
                R"("a": { "type": "filter", "inputs": { "image": "src.image" }, "bypass": true })"),
            std::string::npos)
      << saved;
  EXPECT_NE(saved.find(R"("editor": { "positions": { "src": [0, 0], "a": [250, 0] } })"),
            std::string::npos)
      << saved;
  fs::remove(path);
}

TEST(NodeTooltip, SaysEachReasonOnceInTheEditorsTerms) {
  const auto reasons = node_reasons(
      {"required input \"image\" (image) is not connected: add \"inputs\": {\"image\": "
       "\"<node>.<port>\"}"},
      "node 'tint' (tint): required input 'image' is not connected");
  ASSERT_EQ(reasons.size(), 1u);
  EXPECT_EQ(reasons[0],
            "required input \"image\" (image) is not connected: drag a link from an output port "
            "onto it");
  const auto twice = node_reasons({"bad value", "bad value"}, "bad value");
  EXPECT_EQ(twice.size(), 1u);
  EXPECT_EQ(node_reasons({}, "shader failed").size(), 1u);
}

TEST(EvalPolicy, DraftOnlyWhenTheFullEvaluationCannotKeepUp) {
  DraftInputs typed;
  typed.last_full_ms = 400;  // the flagship graph's full evaluation
  EXPECT_FALSE(evaluate_as_draft(typed)) << "a typed value evaluates in full";
  DraftInputs drag = typed;
  drag.gesture = true;
  EXPECT_TRUE(evaluate_as_draft(drag)) << "a drag cannot wait 400 ms per step";
  drag.last_full_ms = kGestureBudgetMs * 0.8;
  EXPECT_FALSE(evaluate_as_draft(drag)) << "a fast graph drags in full";
  DraftInputs play = typed;
  play.playing = true;
  play.fps = 24;
  play.last_full_ms = 30;
  EXPECT_FALSE(evaluate_as_draft(play)) << "30 ms keeps up with 24 fps";
  play.last_full_ms = 60;
  EXPECT_TRUE(evaluate_as_draft(play));
  play.graph_is_draft = true;
  EXPECT_FALSE(evaluate_as_draft(play)) << "a draft graph has no smaller draft";
  DraftInputs unknown;
  unknown.gesture = true;
  EXPECT_FALSE(evaluate_as_draft(unknown)) << "no full evaluation measured yet";
}

TEST(FrameStats, SummarySplitsFramesDrawnWhileEvaluating) {
  FrameStats stats;
  for (int i = 0; i < 10; ++i) stats.add(10.0, false);
  for (int i = 0; i < 10; ++i) stats.add(20.0, true);
  EXPECT_EQ(stats.frames(), 20u);
  EXPECT_EQ(stats.frames_while_evaluating(), 10u);
  EXPECT_DOUBLE_EQ(stats.recent_ms(), 15.0);
  const std::string summary = stats.summary();
  EXPECT_NE(summary.find("UI frames: 20 (10 while evaluating)"), std::string::npos) << summary;
  EXPECT_NE(summary.find("while evaluating median 20.0 ms"), std::string::npos) << summary;
  EXPECT_DOUBLE_EQ(quantile({3, 1, 2}, 0.5), 2.0);
  EXPECT_DOUBLE_EQ(quantile({}, 0.5), 0.0);
}

TEST(FileChooser, ListsFoldersThenGraphFilesWithoutSideFiles) {
  const fs::path dir = fs::temp_directory_path() / "aq_file_chooser_test";
  fs::remove_all(dir);
  fs::create_directories(dir / "sub");
  for (const char* name : {"b.json", "a.json", "a.autosave.json", "notes.txt", ".hidden.json"}) {
    std::ofstream(dir / name) << "{}";
  }
  auto graphs = list_folder(dir.string(), {".json"});
  ASSERT_EQ(graphs.size(), 3u);
  EXPECT_EQ(graphs[0].name, "sub");
  EXPECT_TRUE(graphs[0].is_folder);
  EXPECT_EQ(graphs[1].name, "a.json");
  EXPECT_EQ(graphs[2].name, "b.json");
  EXPECT_EQ(list_folder(dir.string(), {}).size(), 4u) << "all files: notes.txt too";
  fs::remove_all(dir);
}

TEST(ImageView, FitsCentredZoomsAtTheCursorAndPans) {
  ImageView view;
  view.place(1280, 720, 640, 480);
  EXPECT_FLOAT_EQ(view.zoom, 0.5f);
  EXPECT_FLOAT_EQ(view.pan_y, (480 - 360) * 0.5f);
  float x = 0;
  float y = 0;
  view.pixel_at(320, 240, &x, &y);
  EXPECT_EQ(x, 640);
  EXPECT_EQ(y, 360);
  // The wheel at a point keeps the pixel under it; fitting stops until asked again.
  view.pixel_at(100, 200, &x, &y);
  view.zoom_to(100, 200, 4.0f);
  float after_x = 0;
  float after_y = 0;
  view.pixel_at(100, 200, &after_x, &after_y);
  EXPECT_EQ(after_x, x);
  EXPECT_EQ(after_y, y);
  EXPECT_FALSE(view.fit);
  view.place(1280, 720, 640, 480);
  EXPECT_FLOAT_EQ(view.zoom, 4.0f) << "not refitted while the user zooms";
  view.pan_by(40, -10);
  view.pixel_at(140, 190, &after_x, &after_y);
  EXPECT_EQ(after_x, x);
  EXPECT_EQ(after_y, y);
}

}  // namespace
}  // namespace aq::editor
