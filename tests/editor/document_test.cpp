// The editor's document model without GL: every edit kind undoes and redoes exactly, refused
// links say why and leave the graph alone, ids and positions survive save and load, autosave
// and recovery.
// The test executables link only the test support library, not the editor's: the model under
// test is compiled in here (it needs the core library alone, no GL and no window).
#include "editor/document.h"

#include <aquarelle/core/graph_io.h>
#include <aquarelle/core/registry.h>
#include <gtest/gtest.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <thread>
#include <tuple>
#include <utility>
#include <vector>

namespace aq::editor {
namespace {

namespace fs = std::filesystem;

PortInfo port(const std::string& name, aq_port_type type, bool optional = false) {
  PortInfo info;
  info.name = name;
  info.type = type;
  info.optional = optional;
  return info;
}

ParamInfo float_param(const std::string& name, double def, double lo, double hi) {
  ParamInfo info;
  info.name = name;
  info.type = AQ_PARAM_FLOAT;
  info.default_value[0] = def;
  info.min_value = lo;
  info.max_value = hi;
  return info;
}

// A small registry of hand-made types, so these tests need no plugin and no GL.
const Registry& test_registry() {
  static const Registry registry = [] {
    Registry r;
    std::string why;
    NodeType source;
    source.name = "source";
    source.category = "Texture";
    source.outputs = {port("image", AQ_PORT_IMAGE)};
    EXPECT_TRUE(r.add(source, &why)) << why;

    NodeType blur;
    blur.name = "blur";
    blur.category = "Filter";
    blur.inputs = {port("image", AQ_PORT_IMAGE), port("depth", AQ_PORT_IMAGE, true)};
    blur.outputs = {port("image", AQ_PORT_IMAGE)};
    ParamInfo method;
    method.name = "method";
    method.type = AQ_PARAM_ENUM;
    method.enum_values = {"gaussian", "strided"};
    ParamInfo taps;
    taps.name = "taps";
    taps.type = AQ_PARAM_INT;
    taps.default_value[0] = 5;
    taps.min_value = 1;
    taps.max_value = 31;
    blur.params = {float_param("sigma", 3.0, 0.0, 50.0), method, taps};
    EXPECT_TRUE(r.add(blur, &why)) << why;

    NodeType scene;
    scene.name = "scene";
    scene.category = "Scene";
    scene.outputs = {port("scene", AQ_PORT_SCENE)};
    EXPECT_TRUE(r.add(scene, &why)) << why;

    NodeType gbuffer;
    gbuffer.name = "gbuffer";
    gbuffer.category = "Scene";
    gbuffer.inputs = {port("scene", AQ_PORT_SCENE)};
    gbuffer.outputs = {port("albedo", AQ_PORT_IMAGE), port("depth", AQ_PORT_IMAGE)};
    EXPECT_TRUE(r.add(gbuffer, &why)) << why;
    return r;
  }();
  return registry;
}

class DocumentTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ =
        fs::temp_directory_path() /
        ("aq_document_test_" + std::to_string(::testing::UnitTest::GetInstance()->random_seed()) +
         "_" + ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }

  // source → blur → (output), scene → gbuffer, gbuffer.depth → blur.depth
  void build_chain() {
    ASSERT_EQ(doc.add_node("source", {0, 0}).value(), "source");
    ASSERT_EQ(doc.add_node("blur", {200, 0}).value(), "blur");
    ASSERT_EQ(doc.add_node("scene", {0, 200}).value(), "scene");
    ASSERT_EQ(doc.add_node("gbuffer", {200, 200}).value(), "gbuffer");
    ASSERT_TRUE(doc.link({"source", "image"}, "blur", "image"));
    ASSERT_TRUE(doc.link({"scene", "scene"}, "gbuffer", "scene"));
    ASSERT_TRUE(doc.link({"gbuffer", "depth"}, "blur", "depth"));
    ASSERT_TRUE(doc.set_output(PortRef{"blur", "image"}));
  }

  std::string text() const { return write_graph_text(doc.graph()); }

  Document doc{test_registry()};
  fs::path dir_;
};

TEST_F(DocumentTest, NewIdsFollowTheTypeName) {
  EXPECT_EQ(doc.add_node("blur", {0, 0}).value(), "blur");
  EXPECT_EQ(doc.add_node("blur", {0, 0}).value(), "blur2");
  EXPECT_EQ(doc.add_node("blur", {0, 0}).value(), "blur3");
  EXPECT_EQ(doc.add_node("blur", {0, 0}, "soft").value(), "soft");
  EXPECT_FALSE(doc.add_node("blur", {0, 0}, "soft").ok());
  auto unknown = doc.add_node("no_such_type", {0, 0});
  ASSERT_FALSE(unknown.ok());
  EXPECT_NE(unknown.message().find("no_such_type"), std::string::npos) << unknown.message();
  EXPECT_NE(unknown.message().find("installed"), std::string::npos) << unknown.message();
}

TEST_F(DocumentTest, UndoRedoAddNode) {
  ASSERT_TRUE(doc.add_node("blur", {10, 20}).ok());
  const std::string after_add = text();
  ASSERT_TRUE(doc.undo());
  EXPECT_TRUE(doc.graph().nodes.empty());
  EXPECT_FALSE(doc.position("blur").has_value());
  ASSERT_TRUE(doc.redo());
  EXPECT_EQ(text(), after_add);
  EXPECT_EQ(doc.position("blur"), (Position{10, 20}));
}

TEST_F(DocumentTest, UndoRedoLinkAndUnlink) {
  build_chain();
  const std::string linked = text();
  ASSERT_TRUE(doc.unlink("blur", "image"));
  EXPECT_FALSE(doc.graph().nodes.at("blur").inputs.count("image"));
  ASSERT_TRUE(doc.undo());
  EXPECT_EQ(text(), linked);
  ASSERT_TRUE(doc.redo());
  EXPECT_FALSE(doc.graph().nodes.at("blur").inputs.count("image"));
  // Undo the unlink, then the link itself.
  ASSERT_TRUE(doc.undo());
  ASSERT_TRUE(doc.undo());  // set_output
  ASSERT_TRUE(doc.undo());  // gbuffer.depth → blur.depth
  EXPECT_FALSE(doc.graph().nodes.at("blur").inputs.count("depth"));
  EXPECT_TRUE(doc.graph().nodes.at("blur").inputs.count("image"));
}

TEST_F(DocumentTest, RelinkingAnInputReplacesItsSourceAndUndoRestoresIt) {
  build_chain();
  ASSERT_TRUE(doc.add_node("source", {0, 100}).ok());  // source2
  ASSERT_TRUE(doc.link({"source2", "image"}, "blur", "image"));
  EXPECT_EQ(doc.graph().nodes.at("blur").inputs.at("image"), (PortRef{"source2", "image"}));
  ASSERT_TRUE(doc.undo());
  EXPECT_EQ(doc.graph().nodes.at("blur").inputs.at("image"), (PortRef{"source", "image"}));
}

TEST_F(DocumentTest, RefusedLinksSayWhyAndChangeNothing) {
  build_chain();
  ASSERT_TRUE(doc.add_node("blur", {400, 0}).ok());  // blur2
  ASSERT_TRUE(doc.link({"blur", "image"}, "blur2", "image"));
  const std::string before = text();
  const std::string undo_label = doc.undo_label();

  struct Case {
    PortRef from;
    std::string node, input, expected;
  };
  const Case cases[] = {
      {{"scene", "scene"}, "blur", "image", "incompatible port types"},
      {{"blur", "image"}, "gbuffer", "scene", "incompatible port types"},
      {{"blur2", "image"}, "blur", "image", "cycle"},
      {{"blur", "image"}, "blur", "depth", "its own output"},
      {{"blur", "colour"}, "blur2", "image", "no output 'colour'"},
      {{"blur", "image"}, "blur2", "mask", "no input 'mask'"},
      {{"nowhere", "image"}, "blur2", "image", "no node 'nowhere'"},
      {{"blur", "image"}, "nowhere", "image", "no node 'nowhere'"},
  };
  for (const Case& c : cases) {
    Status linked = doc.link(c.from, c.node, c.input);
    ASSERT_FALSE(linked.ok()) << c.from.str() << " → " << c.node << "." << c.input;
    EXPECT_NE(linked.message().find(c.expected), std::string::npos) << linked.message();
    EXPECT_EQ(doc.why_not_link(c.from, c.node, c.input), linked.message());
  }
  EXPECT_EQ(text(), before);
  EXPECT_EQ(doc.undo_label(), undo_label);
  EXPECT_EQ(doc.why_not_link({"source", "image"}, "blur2", "depth"), "");
}

TEST_F(DocumentTest, UndoRedoDeleteRestoresLinksOutputAndPosition) {
  build_chain();
  const std::string full = text();
  ASSERT_TRUE(doc.remove_nodes({"gbuffer"}));
  EXPECT_FALSE(doc.graph().nodes.count("gbuffer"));
  EXPECT_FALSE(doc.graph().nodes.at("blur").inputs.count("depth"));
  EXPECT_FALSE(doc.position("gbuffer").has_value());
  ASSERT_TRUE(doc.remove_nodes({"blur", "source"}));
  EXPECT_FALSE(doc.graph().output.has_value());
  ASSERT_TRUE(doc.undo());
  ASSERT_TRUE(doc.undo());
  EXPECT_EQ(text(), full);
  ASSERT_TRUE(doc.redo());
  ASSERT_TRUE(doc.redo());
  EXPECT_EQ(doc.graph().nodes.size(), 1u);
  EXPECT_FALSE(doc.remove_nodes({"nowhere"}).ok());
}

TEST_F(DocumentTest, UndoRedoMoveAndOneStepPerDrag) {
  build_chain();
  const std::string placed = text();
  // A drag: many moves with one key are one undo step.
  for (int i = 1; i <= 5; ++i) {
    ASSERT_TRUE(
        doc.move_nodes({{"blur", {200.0f + i * 10, 0}}, {"source", {0, i * 5.0f}}}, "drag"));
  }
  doc.end_gesture();
  EXPECT_EQ(doc.position("blur"), (Position{250, 0}));
  EXPECT_EQ(doc.position("source"), (Position{0, 25}));
  ASSERT_TRUE(doc.move_nodes({{"blur", {300, 300}}}, "drag"));  // a second drag
  doc.end_gesture();
  ASSERT_TRUE(doc.undo());
  EXPECT_EQ(doc.position("blur"), (Position{250, 0}));
  ASSERT_TRUE(doc.undo());
  EXPECT_EQ(text(), placed);
  ASSERT_TRUE(doc.redo());
  EXPECT_EQ(doc.position("blur"), (Position{250, 0}));
  EXPECT_EQ(doc.position("source"), (Position{0, 25}));
}

TEST_F(DocumentTest, UndoRedoParameterChangeAndItsChecks) {
  build_chain();
  const std::string defaults = text();
  ASSERT_TRUE(doc.set_param("blur", "sigma", 7.5));
  EXPECT_EQ(doc.graph().nodes.at("blur").params.at("sigma"), 7.5);
  ASSERT_TRUE(doc.set_param("blur", "method", "strided"));
  ASSERT_TRUE(doc.set_param("blur", "taps", 9.0));
  EXPECT_TRUE(doc.graph().nodes.at("blur").params.at("taps").is_number_integer());

  const std::string set = text();
  Status out_of_range = doc.set_param("blur", "sigma", 80.0);
  ASSERT_FALSE(out_of_range.ok());
  EXPECT_NE(out_of_range.message().find("outside its range"), std::string::npos);
  Status bad_enum = doc.set_param("blur", "method", "box");
  ASSERT_FALSE(bad_enum.ok());
  EXPECT_NE(bad_enum.message().find("gaussian, strided"), std::string::npos) << bad_enum.message();
  EXPECT_FALSE(doc.set_param("blur", "sigma", "wide").ok());
  EXPECT_FALSE(doc.set_param("blur", "taps", 2.5).ok());
  EXPECT_FALSE(doc.set_param("blur", "radius", 1.0).ok());
  EXPECT_FALSE(doc.set_param("nowhere", "sigma", 1.0).ok());
  EXPECT_EQ(text(), set);

  // A slider drag is one undo step; null resets to the default.
  for (double s : {1.0, 2.0, 4.0}) ASSERT_TRUE(doc.set_param("blur", "sigma", s, "slider"));
  doc.end_gesture();
  ASSERT_TRUE(doc.undo());
  EXPECT_EQ(text(), set);
  ASSERT_TRUE(doc.set_param("blur", "sigma", nullptr));
  EXPECT_FALSE(doc.graph().nodes.at("blur").params.count("sigma"));
  ASSERT_TRUE(doc.undo());
  ASSERT_TRUE(doc.undo());
  ASSERT_TRUE(doc.undo());
  ASSERT_TRUE(doc.undo());
  EXPECT_EQ(text(), defaults);
}

TEST_F(DocumentTest, UndoRedoDuplicateKeepsLinks) {
  build_chain();
  ASSERT_TRUE(doc.set_param("blur", "sigma", 9.0));
  const std::string before = text();
  auto copies = doc.duplicate_nodes({"gbuffer", "blur"});
  ASSERT_TRUE(copies.ok()) << copies.message();
  ASSERT_EQ(copies->size(), 2u);
  EXPECT_EQ((*copies)[0], "gbuffer2");
  EXPECT_EQ((*copies)[1], "blur2");
  const Node& blur2 = doc.graph().nodes.at("blur2");
  EXPECT_EQ(blur2.params.at("sigma"), 9.0);
  // Links among the copies point at the copies; links from outside stay.
  EXPECT_EQ(blur2.inputs.at("depth"), (PortRef{"gbuffer2", "depth"}));
  EXPECT_EQ(blur2.inputs.at("image"), (PortRef{"source", "image"}));
  EXPECT_EQ(doc.graph().nodes.at("gbuffer2").inputs.at("scene"), (PortRef{"scene", "scene"}));
  EXPECT_EQ(doc.position("blur2"), (Position{240, 40}));
  ASSERT_TRUE(doc.undo());
  EXPECT_EQ(text(), before);
  ASSERT_TRUE(doc.redo());
  EXPECT_TRUE(doc.graph().nodes.count("blur2"));
}

TEST_F(DocumentTest, UndoRedoOutputAndSettings) {
  build_chain();
  ASSERT_TRUE(doc.set_output(PortRef{"gbuffer", "depth"}));
  EXPECT_FALSE(doc.set_output(PortRef{"gbuffer", "normal"}).ok());
  Settings settings = doc.graph().settings;
  settings.width = 320;
  ASSERT_TRUE(doc.set_settings(settings));
  ASSERT_TRUE(doc.undo());
  EXPECT_EQ(doc.graph().settings.width, Settings{}.width);
  ASSERT_TRUE(doc.undo());
  EXPECT_EQ(doc.graph().output, (PortRef{"blur", "image"}));
  ASSERT_TRUE(doc.redo());
  EXPECT_EQ(doc.graph().output, (PortRef{"gbuffer", "depth"}));
}

TEST_F(DocumentTest, NewEditClearsRedo) {
  build_chain();
  ASSERT_TRUE(doc.undo());
  EXPECT_TRUE(doc.can_redo());
  ASSERT_TRUE(doc.add_node("source", {0, 0}).ok());
  EXPECT_FALSE(doc.can_redo());
}

TEST_F(DocumentTest, DirtyFlagFollowsSaveUndoAndRedo) {
  EXPECT_FALSE(doc.dirty());
  build_chain();
  EXPECT_TRUE(doc.dirty());
  EXPECT_FALSE(doc.save().ok());  // no file yet
  const std::string path = (dir_ / "g.json").string();
  ASSERT_TRUE(doc.save_as(path));
  EXPECT_FALSE(doc.dirty());
  ASSERT_TRUE(doc.set_param("blur", "sigma", 2.0, "slider"));
  EXPECT_TRUE(doc.dirty());
  ASSERT_TRUE(doc.undo());
  EXPECT_FALSE(doc.dirty());
  ASSERT_TRUE(doc.redo());
  EXPECT_TRUE(doc.dirty());
  ASSERT_TRUE(doc.save());
  EXPECT_FALSE(doc.dirty());
  // The slider gesture was saved: a later drag with the same key must not merge into it.
  ASSERT_TRUE(doc.set_param("blur", "sigma", 3.5, "slider"));
  EXPECT_TRUE(doc.dirty());
}

TEST_F(DocumentTest, IdsLinksAndPositionsSurviveSaveAndLoad) {
  build_chain();
  ASSERT_TRUE(doc.add_node("blur", {400, 0}).ok());
  ASSERT_TRUE(doc.link({"blur", "image"}, "blur2", "image"));
  ASSERT_TRUE(doc.set_param("blur2", "sigma", 1.5));
  const std::string path = (dir_ / "chain.json").string();
  ASSERT_TRUE(doc.save_as(path));

  // The file holds positions under editor.positions, keyed by the same ids.
  std::ifstream in(path);
  nlohmann::json file = nlohmann::json::parse(in);
  ASSERT_TRUE(file.contains("editor")) << file.dump(2);
  EXPECT_EQ(file["editor"]["positions"]["blur2"], nlohmann::json::array({400, 0}));
  EXPECT_EQ(file["editor"]["positions"]["gbuffer"], nlohmann::json::array({200, 200}));
  EXPECT_EQ(file["nodes"]["blur2"]["inputs"]["image"], "blur.image");

  Document loaded(test_registry());
  ASSERT_TRUE(loaded.open(path));
  EXPECT_FALSE(loaded.dirty());
  EXPECT_EQ(write_graph_text(loaded.graph()), write_graph_text(doc.graph()));
  for (const auto& [id, node] : doc.graph().nodes) {
    ASSERT_TRUE(loaded.graph().nodes.count(id)) << id;
    EXPECT_EQ(loaded.position(id), doc.position(id)) << id;
  }
  // Editing the loaded graph hands out ids that do not collide with the saved ones.
  EXPECT_EQ(loaded.add_node("blur", {0, 0}).value(), "blur3");
}

TEST_F(DocumentTest, SaveAsksBeforeOverwritingAFileChangedOnDisk) {
  build_chain();
  const std::string path = (dir_ / "shared.json").string();
  ASSERT_TRUE(doc.save_as(path));
  ASSERT_TRUE(doc.set_param("blur", "sigma", 2.0));
  ASSERT_TRUE(doc.save()) << "unchanged on disk: saves without asking";

  // Someone else rewrites the file (a later modification time).
  std::string theirs = "{\"aquarelle\": 1, \"nodes\": {}}\n";
  std::ofstream(path) << theirs;
  fs::last_write_time(path, fs::last_write_time(path) + std::chrono::seconds(5));
  ASSERT_TRUE(doc.set_param("blur", "sigma", 3.0));
  Status refused = doc.save();
  ASSERT_FALSE(refused.ok());
  EXPECT_NE(refused.message().find("changed on disk"), std::string::npos) << refused.message();
  std::ifstream kept(path);
  std::stringstream text;
  text << kept.rdbuf();
  EXPECT_EQ(text.str(), theirs) << "their file is untouched until the user confirms";

  EXPECT_TRUE(doc.save()) << "saving again is the confirmation";
  std::ifstream ours(path);
  nlohmann::json file = nlohmann::json::parse(ours);
  EXPECT_EQ(file["nodes"]["blur"]["params"]["sigma"], 3.0);
}

TEST_F(DocumentTest, OpenRefusesTextThatIsNotJson) {
  const std::string path = (dir_ / "broken.json").string();
  std::ofstream(path) << "{ \"aquarelle\": 1, \"nodes\": { ";
  Status opened = doc.open(path);
  ASSERT_FALSE(opened.ok());
  EXPECT_NE(opened.message().find("broken.json"), std::string::npos) << opened.message();
  EXPECT_FALSE(doc.open((dir_ / "missing.json").string()).ok());
}

TEST_F(DocumentTest, OpenKeepsAGraphWithProblemsAndListsThem) {
  const std::string path = (dir_ / "unknown.json").string();
  std::ofstream(path) << R"({"aquarelle": 1, "nodes": {"x": {"type": "no_such_type"}}})";
  ASSERT_TRUE(doc.open(path));
  EXPECT_TRUE(doc.graph().nodes.count("x"));
  EXPECT_FALSE(doc.problems_of("x").empty());
}

TEST_F(DocumentTest, AutosaveAndRecovery) {
  const std::string path = (dir_ / "work.json").string();
  build_chain();
  ASSERT_TRUE(doc.save_as(path));
  EXPECT_EQ(doc.autosave_path(), (dir_ / "work.autosave.json").string());
  EXPECT_FALSE(doc.autosave().value());  // nothing unsaved
  EXPECT_FALSE(doc.has_recovery());

  ASSERT_TRUE(doc.set_param("blur", "sigma", 12.0));
  ASSERT_TRUE(doc.add_node("source", {5, 5}).ok());
  ASSERT_TRUE(doc.autosave().value());
  EXPECT_FALSE(doc.autosave().value());  // unchanged since
  EXPECT_TRUE(fs::exists(doc.autosave_path()));
  const std::string unsaved = text();

  // "Crash": a new session opens the file and finds the side file.
  Document next(test_registry());
  ASSERT_TRUE(next.open(path));
  EXPECT_TRUE(next.has_recovery());
  EXPECT_NE(write_graph_text(next.graph()), unsaved);
  ASSERT_TRUE(next.recover());
  EXPECT_EQ(write_graph_text(next.graph()), unsaved);
  EXPECT_TRUE(next.dirty());
  ASSERT_TRUE(next.undo());  // recovery is an undoable step
  EXPECT_FALSE(next.graph().nodes.count("source2"));
  ASSERT_TRUE(next.redo());
  ASSERT_TRUE(next.save());
  EXPECT_FALSE(fs::exists(next.autosave_path()));
  EXPECT_FALSE(next.has_recovery());

  // Declining the offer removes the side file.
  ASSERT_TRUE(next.set_param("blur", "sigma", 1.0));
  ASSERT_TRUE(next.autosave().value());
  Document third(test_registry());
  ASSERT_TRUE(third.open(path));
  ASSERT_TRUE(third.has_recovery());
  third.discard_recovery();
  EXPECT_FALSE(third.has_recovery());
}

// ---- Data safety: what a save writes -----------------------------------------------------

std::string read_file(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

std::vector<std::string> lines_of(const std::string& text) {
  std::vector<std::string> lines;
  std::stringstream in(text);
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  return lines;
}

// The lines of `after` that differ from `before`, after their common head and tail.
std::pair<std::vector<std::string>, std::vector<std::string>> changed_lines(
    const std::string& before, const std::string& after) {
  auto a = lines_of(before);
  auto b = lines_of(after);
  size_t head = 0;
  while (head < a.size() && head < b.size() && a[head] == b[head]) ++head;
  size_t tail = 0;
  while (tail < a.size() - head && tail < b.size() - head &&
         a[a.size() - 1 - tail] == b[b.size() - 1 - tail]) {
    ++tail;
  }
  return {{a.begin() + head, a.end() - tail}, {b.begin() + head, b.end() - tail}};
}

TEST_F(DocumentTest, SaveAsAsksBeforeReplacingAnotherFile) {
  build_chain();
  const std::string mine = (dir_ / "mine.json").string();
  const std::string other = (dir_ / "other.json").string();
  const std::string theirs = "{\"aquarelle\": 1, \"nodes\": {}}\n";
  std::ofstream(other) << theirs;
  EXPECT_TRUE(doc.would_replace(other));
  Status refused = doc.save_as(other);
  ASSERT_FALSE(refused.ok());
  EXPECT_NE(refused.message().find("exists already"), std::string::npos) << refused.message();
  EXPECT_EQ(read_file(other), theirs);
  EXPECT_TRUE(doc.dirty());

  EXPECT_FALSE(doc.would_replace(mine)) << "a new file needs no question";
  ASSERT_TRUE(doc.save_as(mine));
  EXPECT_FALSE(doc.would_replace(mine)) << "the graph's own file is saved over without asking";
  ASSERT_TRUE(doc.save_as(mine));
  ASSERT_TRUE(doc.save_as(other, /*replace=*/true)) << "replacing once the user confirmed";
  EXPECT_NE(read_file(other), theirs);
}

TEST_F(DocumentTest, SliderFloatsSaveAsTheirShortestDecimal) {
  build_chain();
  // What an ImGui float slider hands over after typing 0.3 or 0.9.
  ASSERT_TRUE(doc.set_param("blur", "sigma", static_cast<double>(0.3f)));
  EXPECT_EQ(doc.graph().nodes.at("blur").params.at("sigma").get<double>(), 0.3);
  const std::string path = (dir_ / "typed.json").string();
  ASSERT_TRUE(doc.save_as(path));
  std::string text = read_file(path);
  EXPECT_NE(text.find("\"sigma\": 0.3\n"), std::string::npos) << text;
  EXPECT_EQ(text.find("0.30000001"), std::string::npos) << text;
  // A float that reads back the same keeps its shortest text; a double stays exact.
  EXPECT_EQ(shortest_number(static_cast<double>(0.9f)).dump(), "0.9");
  EXPECT_EQ(shortest_number(0.1 + 0.2).dump(), nlohmann::json(0.1 + 0.2).dump());
  EXPECT_EQ(shortest_number(5).dump(), "5");
}

TEST_F(DocumentTest, EveryRepositoryGraphSavesToTheSameBytes) {
  int graphs = 0;
  for (const auto& entry : fs::directory_iterator(fs::path(AQ_SOURCE_DIR) / "graphs")) {
    if (entry.path().extension() != ".json") continue;
    const std::string path = (dir_ / entry.path().filename()).string();
    fs::copy_file(entry.path(), path);
    Document copy(test_registry());  // types unknown here: the graph opens with problems
    ASSERT_TRUE(copy.open(path)) << path;
    ASSERT_TRUE(copy.save()) << path;
    EXPECT_EQ(read_file(path), read_file(entry.path().string())) << entry.path();
    ++graphs;
  }
  EXPECT_GE(graphs, 5);
}

TEST_F(DocumentTest, AnEditChangesOnlyTheLinesItConcerns) {
  // The flagship graph's layout: Python-style arrays, one value per line, integer positions.
  const std::string original = R"({
  "aquarelle": 1,
  "settings": {
    "width": 640,
    "height": 360,
    "frames": [
      1,
      48
    ]
  },
  "nodes": {
    "src": {
      "type": "source"
    },
    "soft": {
      "type": "blur",
      "params": {
        "taps": 5,
        "sigma": 1.0
      },
      "inputs": {
        "image": "src.image"
      }
    }
  },
  "output": "soft.image",
  "editor": {
    "positions": {
      "src": [
        40,
        60
      ],
      "soft": [
        1840,
        60
      ]
    }
  }
}
)";
  const std::string path = (dir_ / "flagship_like.json").string();
  std::ofstream(path) << original;
  ASSERT_TRUE(doc.open(path));
  ASSERT_TRUE(doc.save());
  EXPECT_EQ(read_file(path), original) << "unedited: the same bytes";

  // A move changes the one coordinate line; "1.0" and the key order stay as written.
  ASSERT_TRUE(doc.move_nodes({{"soft", {1900.4f, 60}}}));
  ASSERT_TRUE(doc.save());
  auto [before, after] = changed_lines(original, read_file(path));
  EXPECT_EQ(before, std::vector<std::string>{"        1840,"});
  EXPECT_EQ(after, std::vector<std::string>{"        1900,"});

  // A parameter edit changes its own line.
  const std::string moved = read_file(path);
  ASSERT_TRUE(doc.set_param("soft", "taps", 7));
  ASSERT_TRUE(doc.save());
  std::tie(before, after) = changed_lines(moved, read_file(path));
  EXPECT_EQ(before, std::vector<std::string>{"        \"taps\": 5,"});
  EXPECT_EQ(after, std::vector<std::string>{"        \"taps\": 7,"});

  // A new node is inserted, in the file's style, and nothing else moves.
  const std::string edited = read_file(path);
  ASSERT_TRUE(doc.add_node("source", {40, 200}).ok());
  ASSERT_TRUE(doc.save());
  const std::string added = read_file(path);
  // Every old line is still there, in order (a comma added after the last member aside), and
  // the new lines are the node's three and its position's four.
  auto strip = [](std::vector<std::string> lines) {
    for (auto& line : lines) {
      if (!line.empty() && line.back() == ',') line.pop_back();
    }
    return lines;
  };
  const auto old_lines = strip(lines_of(edited));
  const auto new_lines = strip(lines_of(added));
  size_t found = 0;
  for (const auto& line : new_lines) {
    if (found < old_lines.size() && line == old_lines[found]) ++found;
  }
  EXPECT_EQ(found, old_lines.size()) << added;
  EXPECT_EQ(new_lines.size(), old_lines.size() + 7) << added;
  auto reread = nlohmann::json::parse(added);
  EXPECT_EQ(reread["nodes"]["source"]["type"], "source");
  EXPECT_EQ(reread["editor"]["positions"]["source"], nlohmann::json::array({40, 200}));
  EXPECT_NE(added.find("      \"source\": [\n        40,\n        200\n      ]"), std::string::npos)
      << added;

  // Deleting it gives the previous text back.
  ASSERT_TRUE(doc.remove_nodes({"source"}));
  ASSERT_TRUE(doc.save());
  EXPECT_EQ(read_file(path), edited);
}

TEST_F(DocumentTest, AHandWrittenGraphKeepsItsInlineStyleAndGainsNoPositionsUnedited) {
  const std::string original =
      "{\n  \"aquarelle\": 1,\n"
      "  \"settings\": { \"width\": 64, \"height\": 64, \"fps\": 24, \"frames\": [1, 1] },\n"
      "  \"nodes\": {\n"
      "    \"src\": { \"type\": \"source\" },\n"
      "    \"soft\": { \"type\": \"blur\", \"params\": { \"sigma\": 2.0 }, \"inputs\": { "
      "\"image\": \"src.image\" } }\n"
      "  },\n  \"output\": \"soft.image\"\n}\n";
  const std::string path = (dir_ / "inline.json").string();
  std::ofstream(path) << original;
  ASSERT_TRUE(doc.open(path));
  EXPECT_TRUE(doc.position("soft")) << "placed for the canvas";
  ASSERT_TRUE(doc.save());
  EXPECT_EQ(read_file(path), original) << "automatic positions are not the user's edit";

  ASSERT_TRUE(doc.set_param("soft", "taps", 9));
  ASSERT_TRUE(doc.save());
  const std::string text = read_file(path);
  EXPECT_NE(text.find("\"params\": { \"sigma\": 2.0, \"taps\": 9 }"), std::string::npos) << text;
  EXPECT_NE(
      text.find("\"settings\": { \"width\": 64, \"height\": 64, \"fps\": 24, \"frames\": [1, 1] }"),
      std::string::npos)
      << text;
  EXPECT_TRUE(nlohmann::json::parse(text)["editor"]["positions"].contains("soft")) << text;
}

}  // namespace
}  // namespace aq::editor
