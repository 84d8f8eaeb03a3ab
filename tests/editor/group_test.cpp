// Node groups without a window: Ctrl+G collapses the selection into one canvas node whose ports
// are the links crossing the group's boundary (plus its members' free inputs and its result),
// links made at a group's port reach the inner node, moving the group moves its nodes, the
// group is saved in editor.groups and reads back byte-stably, undo/redo cover group, collapse,
// expand and ungroup, deleting and renaming keep groups consistent.
#include "editor/canvas_view.h"
#include "editor/document.h"
#include "editor/editor_actions.h"
#include "editor/fake_node_types.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>

namespace aq::editor {
namespace {

namespace fs = std::filesystem;

const Registry& registry() {
  return test::fake_registry();
}

std::string read_text(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

const NodeLayout* find(const std::vector<NodeLayout>& layouts, const std::string& id) {
  for (const auto& layout : layouts) {
    if (layout.id == id) return &layout;
  }
  return nullptr;
}

// src → a → b → c (output c.image); the group will hold a and b.
class GroupTest : public ::testing::Test {
 protected:
  void SetUp() override {
    ASSERT_TRUE(doc.add_node("source", {0, 0}, "src").ok());
    ASSERT_TRUE(doc.add_node("filter", {250, 0}, "a").ok());
    ASSERT_TRUE(doc.add_node("filter", {500, 40}, "b").ok());
    ASSERT_TRUE(doc.add_node("filter", {750, 0}, "c").ok());
    ASSERT_TRUE(doc.link({"src", "image"}, "a", "image"));
    ASSERT_TRUE(doc.link({"a", "image"}, "b", "image"));
    ASSERT_TRUE(doc.link({"b", "image"}, "c", "image"));
    ASSERT_TRUE(doc.set_output(PortRef{"c", "image"}));
  }
  Document doc{registry()};
  EditorState state{doc};
  const std::string item = group_item_id("Group");
};

TEST_F(GroupTest, CollapsedGroupIsOneNodeWithTheBoundaryLinksAsPorts) {
  actions::select(state, {"a", "b"});
  ASSERT_TRUE(actions::group_selection(state));
  EXPECT_EQ(state.selection, (std::set<std::string>{item}));
  const auto groups = read_groups(doc.graph());
  ASSERT_EQ(groups.size(), 1u);
  EXPECT_EQ(groups[0].nodes, (std::vector<std::string>{"a", "b"}));
  EXPECT_TRUE(groups[0].collapsed);
  EXPECT_EQ(groups[0].position, (Position{250, 0})) << "at its nodes' top-left";

  CanvasView view;
  const auto layouts = layout_graph(doc.graph(), registry(), view, {0, 0});
  EXPECT_EQ(find(layouts, "a"), nullptr) << "members are hidden";
  EXPECT_EQ(find(layouts, "b"), nullptr);
  const NodeLayout* group = find(layouts, item);
  ASSERT_NE(group, nullptr);
  // Inputs: a.image (from src, outside); b.image is fed inside; the optional masks are unlinked.
  std::vector<std::string> inputs, outputs;
  for (const auto& spot : group->inputs) inputs.push_back(spot.node + "." + spot.port);
  for (const auto& spot : group->outputs) outputs.push_back(spot.node + "." + spot.port);
  EXPECT_EQ(inputs, (std::vector<std::string>{"a.image"}));
  // Outputs: b.image is read outside (by c); a.image only inside.
  EXPECT_EQ(outputs, (std::vector<std::string>{"b.image"}));

  // The links crossing the boundary are drawn to and from the group's ports.
  EXPECT_EQ(find_port_spot(layouts, "a", "image", true), &group->inputs[0]);
  EXPECT_EQ(find_port_spot(layouts, "b", "image", false), &group->outputs[0]);
  EXPECT_EQ(find_port_spot(layouts, "b", "image", true), nullptr) << "an inner link is hidden";
  EXPECT_EQ(find_node_layout(layouts, "b"), group);
  // A required input left unlinked is shown, to be linked; a group nobody reads shows its
  // last node's output as its result.
  ASSERT_TRUE(doc.group_nodes({"c"}, "tail").ok());
  ASSERT_TRUE(doc.unlink("c", "image"));
  const Group tail = read_groups(doc.graph())[1];
  ASSERT_TRUE(doc.set_output(std::nullopt));
  const GroupPorts ports = group_ports(doc.graph(), registry(), tail);
  ASSERT_EQ(ports.inputs.size(), 1u);
  EXPECT_EQ(ports.inputs[0].inner, (PortRef{"c", "image"}));
  ASSERT_EQ(ports.outputs.size(), 1u);
  EXPECT_EQ(ports.outputs[0].inner, (PortRef{"c", "image"}));
  ASSERT_TRUE(doc.undo());
  ASSERT_TRUE(doc.undo());
  ASSERT_TRUE(doc.undo());

  // A port of the group is the inner node's: a link made there reaches it.
  auto hit = port_at(layouts, group->inputs[0].at, 4.0f);
  ASSERT_TRUE(hit);
  EXPECT_EQ(hit->node, "a");
  EXPECT_EQ(hit->spot.port, "image");
  ASSERT_TRUE(doc.add_node("source", {0, 300}, "src2").ok());
  ASSERT_TRUE(actions::link(state, {"src2", "image"}, hit->node, hit->spot.port));
  EXPECT_EQ(doc.graph().nodes.at("a").inputs.at("image"), (PortRef{"src2", "image"}));
  auto out = port_at(layouts, group->outputs[0].at, 4.0f);
  ASSERT_TRUE(out);
  EXPECT_EQ(out->node, "b");
  ASSERT_TRUE(actions::link(state, {out->node, out->spot.port}, "c", "mask"));
  EXPECT_EQ(doc.graph().nodes.at("c").inputs.at("mask"), (PortRef{"b", "image"}));
}

TEST_F(GroupTest, MovingTheGroupMovesItsNodesInOneUndoStep) {
  ASSERT_TRUE(doc.group_nodes({"a", "b"}).ok());
  ASSERT_TRUE(actions::move(state, {{item, {300, 10}}}, /*gesture=*/true));
  ASSERT_TRUE(actions::move(state, {{item, {350, 20}}}, /*gesture=*/true));
  actions::end_gesture(state);
  EXPECT_EQ(doc.position("a"), (Position{350, 20}));
  EXPECT_EQ(doc.position("b"), (Position{600, 60}));
  EXPECT_EQ(doc.position("c"), (Position{750, 0}));
  EXPECT_EQ(read_groups(doc.graph())[0].position, (Position{350, 20}));
  EXPECT_EQ(item_position(doc.graph(), item), (Position{350, 20}));
  ASSERT_TRUE(doc.undo());
  EXPECT_EQ(doc.position("a"), (Position{250, 0}));
  EXPECT_EQ(read_groups(doc.graph())[0].position, (Position{250, 0}));
}

TEST_F(GroupTest, UndoRedoCoverGroupCollapseExpandAndUngroup) {
  actions::select(state, {"a", "b"});
  ASSERT_TRUE(actions::group_selection(state));
  ASSERT_TRUE(actions::set_group_collapsed(state, "Group", false));
  EXPECT_EQ(state.selection, (std::set<std::string>{"a", "b"})) << "expanding selects its nodes";
  CanvasView view;
  EXPECT_NE(find(layout_graph(doc.graph(), registry(), view, {0, 0}), "a"), nullptr);
  // Ctrl+G on the nodes of an expanded group collapses it again.
  ASSERT_TRUE(actions::group_selection(state));
  EXPECT_TRUE(read_groups(doc.graph())[0].collapsed);
  EXPECT_EQ(read_groups(doc.graph()).size(), 1u) << "no second group";
  ASSERT_TRUE(actions::ungroup_selection(state));
  EXPECT_TRUE(read_groups(doc.graph()).empty());
  EXPECT_FALSE(doc.graph().editor.contains("groups"));
  EXPECT_EQ(state.selection, (std::set<std::string>{"a", "b"}));

  ASSERT_TRUE(actions::undo(state));  // ungroup
  ASSERT_EQ(read_groups(doc.graph()).size(), 1u);
  EXPECT_TRUE(read_groups(doc.graph())[0].collapsed);
  ASSERT_TRUE(actions::undo(state));  // collapse
  EXPECT_FALSE(read_groups(doc.graph())[0].collapsed);
  ASSERT_TRUE(actions::undo(state));  // expand
  EXPECT_TRUE(read_groups(doc.graph())[0].collapsed);
  ASSERT_TRUE(actions::undo(state));  // group
  EXPECT_TRUE(read_groups(doc.graph()).empty());
  EXPECT_TRUE(state.selection.empty() || !state.selection.count(item)) << "a gone group";
  ASSERT_TRUE(actions::redo(state));
  EXPECT_EQ(read_groups(doc.graph()).size(), 1u);
}

TEST_F(GroupTest, ANodeBelongsToOneGroupAndDeleteAndRenameKeepGroupsConsistent) {
  ASSERT_TRUE(doc.group_nodes({"a", "b"}).ok());
  auto second = doc.group_nodes({"b", "c"});
  ASSERT_FALSE(second.ok());
  EXPECT_NE(second.message().find("in group 'Group'"), std::string::npos);
  ASSERT_TRUE(doc.set_group_collapsed("Group", false));
  ASSERT_TRUE(doc.rename_node("a", "first"));
  EXPECT_EQ(read_groups(doc.graph())[0].nodes, (std::vector<std::string>{"first", "b"}));
  ASSERT_TRUE(doc.set_group_collapsed("Group", true));
  // Deleting a selected collapsed group deletes its nodes, and the group with them.
  actions::select(state, {item});
  ASSERT_TRUE(actions::delete_selection(state));
  EXPECT_FALSE(doc.graph().nodes.count("first"));
  EXPECT_FALSE(doc.graph().nodes.count("b"));
  EXPECT_FALSE(doc.graph().editor.contains("groups"));
  ASSERT_TRUE(doc.undo());
  EXPECT_TRUE(doc.graph().nodes.count("b"));
  EXPECT_EQ(read_groups(doc.graph()).size(), 1u);
  EXPECT_EQ(expand_group_items(doc.graph(), {item, "c"}),
            (std::vector<std::string>{"first", "b", "c"}));
}

TEST_F(GroupTest, GroupsAreSavedInTheEditorSectionAndReadBackByteStably) {
  const fs::path dir = fs::temp_directory_path() / "aq_group_test";
  fs::remove_all(dir);
  fs::create_directories(dir);
  const std::string path = (dir / "grouped.json").string();
  ASSERT_TRUE(doc.group_nodes({"a", "b"}, "smooth").ok());
  ASSERT_TRUE(doc.save_as(path));
  const std::string saved = read_text(path);
  const auto json = nlohmann::json::parse(saved);
  EXPECT_EQ(json["editor"]["groups"],
            nlohmann::json::parse(R"([{"name": "smooth", "nodes": ["a", "b"],
                                      "collapsed": true, "position": [250, 0]}])"));

  // Read back: the same group; saving unedited gives the same bytes.
  Document reopened(registry());
  ASSERT_TRUE(reopened.open(path));
  ASSERT_EQ(read_groups(reopened.graph()).size(), 1u);
  EXPECT_EQ(read_groups(reopened.graph())[0].name, "smooth");
  EXPECT_EQ(reopened.text_to_save(), saved);
  // Expanding and collapsing again is back to the same bytes; expanding changes one line.
  ASSERT_TRUE(reopened.set_group_collapsed("smooth", false));
  const std::string expanded = reopened.text_to_save();
  EXPECT_NE(expanded.find("\"collapsed\": false"), std::string::npos);
  EXPECT_EQ(expanded.size(), saved.size() + 1);  // "true" → "false"
  ASSERT_TRUE(reopened.set_group_collapsed("smooth", true));
  EXPECT_EQ(reopened.text_to_save(), saved);
  fs::remove_all(dir);
}

TEST_F(GroupTest, ACollapsedGroupSitsWhereItsNodesAreAndCanBeRenamed) {
  ASSERT_TRUE(doc.group_nodes({"a", "b"}).ok());
  ASSERT_TRUE(doc.set_group_collapsed("Group", false));
  // Its nodes moved while it was open: it collapses where they are now.
  ASSERT_TRUE(doc.move_nodes({{"a", {260, 100}}, {"b", {520, 90}}}));
  ASSERT_TRUE(doc.set_group_collapsed("Group", true));
  EXPECT_EQ(read_groups(doc.graph())[0].position, (Position{260, 90}));
  // Auto-layout moves the group with its nodes.
  ASSERT_TRUE(actions::auto_layout(state));
  EXPECT_EQ(read_groups(doc.graph())[0].position,
            members_top_left(doc.graph(), registry(), {"a", "b"}));
  // F2 on a selected group renames it; the selection follows.
  actions::select(state, {item});
  ASSERT_TRUE(actions::rename(state, item, "smooth"));
  EXPECT_EQ(read_groups(doc.graph())[0].name, "smooth");
  EXPECT_EQ(state.selection, (std::set<std::string>{group_item_id("smooth")}));
  ASSERT_TRUE(doc.group_nodes({"c"}, "other").ok());
  EXPECT_FALSE(doc.rename_group("other", "smooth")) << "names are unique";
  ASSERT_TRUE(doc.undo());
  ASSERT_TRUE(doc.undo());
  EXPECT_EQ(read_groups(doc.graph())[0].name, "Group");
}

TEST_F(GroupTest, TabWithACollapsedGroupSelectedInsertsAfterItsOutput) {
  actions::select(state, {"a", "b"});
  ASSERT_TRUE(actions::group_selection(state));
  auto inserted = actions::add_node_at_cursor(state, "filter", {600, 300});
  ASSERT_TRUE(inserted.ok());
  EXPECT_EQ(doc.graph().nodes.at(*inserted).inputs.at("image"), (PortRef{"b", "image"}));
  EXPECT_EQ(doc.graph().nodes.at("c").inputs.at("image"), (PortRef{*inserted, "image"}));
}

TEST(GroupFile, AHandWrittenGroupKeepsItsBytesWhenAnotherEditIsSaved) {
  const std::string text = R"({
  "aquarelle": 1,
  "nodes": {
    "src": { "type": "source" },
    "a": { "type": "filter", "inputs": { "image": "src.image" } }
  },
  "output": "a.image",
  "editor": {
    "positions": { "src": [0, 0], "a": [250, 0] },
    "groups": [ { "name": "all", "nodes": ["src", "a"], "collapsed": true, "position": [0, 0] } ]
  }
}
)";
  const fs::path dir = fs::temp_directory_path() / "aq_group_file_test";
  fs::remove_all(dir);
  fs::create_directories(dir);
  const std::string path = (dir / "hand.json").string();
  std::ofstream(path, std::ios::binary) << text;
  Document doc(registry());
  ASSERT_TRUE(doc.open(path));
  EXPECT_EQ(doc.text_to_save(), text);
  // Moving the group rewrites only the numbers that changed.
  ASSERT_TRUE(doc.move_nodes({{group_item_id("all"), {10, 0}}}));
  const std::string moved = doc.text_to_save();
  EXPECT_NE(moved.find("\"positions\": { \"src\": [10, 0], \"a\": [260, 0] }"), std::string::npos)
      << moved;
  EXPECT_NE(moved.find("\"position\": [10, 0]"), std::string::npos) << moved;
  EXPECT_EQ(moved.size(), text.size() + 2);
  fs::remove_all(dir);
}

// A group copied whole comes back with the pasted nodes (in the same or another file), under a
// name not yet taken; a group copied in part does not.
TEST_F(GroupTest, CopyAndPasteCarryAGroupCopiedWhole) {
  actions::select(state, {"a", "b"});
  ASSERT_TRUE(actions::group_selection(state));
  actions::select(state, {item});
  const std::string clipboard = actions::copy_selection(state);
  ASSERT_TRUE(actions::paste(state, clipboard, Position{100, 400}).ok());
  auto groups = read_groups(doc.graph());
  ASSERT_EQ(groups.size(), 2u);
  EXPECT_EQ(groups[1].name, "Group2");
  ASSERT_EQ(groups[1].nodes.size(), 2u);
  for (const auto& id : groups[1].nodes) {
    EXPECT_TRUE(id != "a" && id != "b") << id << " is a copy, not the original";
    EXPECT_TRUE(doc.graph().nodes.count(id)) << id;
  }
  EXPECT_TRUE(groups[1].collapsed);
  EXPECT_EQ(groups[1].position, (Position{100, 400}));

  Document other{registry()};
  EditorState elsewhere{other};
  ASSERT_TRUE(actions::paste(elsewhere, clipboard, std::nullopt).ok());
  groups = read_groups(other.graph());
  ASSERT_EQ(groups.size(), 1u);
  EXPECT_EQ(groups[0].name, "Group");
  EXPECT_EQ(groups[0].nodes, (std::vector<std::string>{"a", "b"}));

  Document part{registry()};
  EditorState partly{part};
  ASSERT_TRUE(actions::paste(partly, doc.copy_nodes({"a"}), std::nullopt).ok());
  EXPECT_TRUE(read_groups(part.graph()).empty());
}

}  // namespace
}  // namespace aq::editor
