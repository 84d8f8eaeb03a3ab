// Tests of reading, validating and writing version-1 graph files (nodes/src/graph_*.cpp).
//
// A Registry of fake node types is built here in C++ (no plugins, no GL). Each kind of problem
// is provoked by a small graph text and the test asserts the problem names the right node,
// field, JSON pointer and line; a file with many mistakes must list all of them. Writing is
// checked against hand-written canonical text, round trips, and atomic saves (including a
// full device and a missing directory). Hostile input (100,000 nested arrays, huge numbers,
// duplicate keys, odd ids) must give problems, never a crash.
#include <gtest/gtest.h>

#include <aquarelle/core/graph_io.h>

#include <sys/stat.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>

namespace {

namespace fs = std::filesystem;

aq::PortInfo port(const char* name, aq_port_type type, bool optional = false) {
  return aq::PortInfo{name, type, optional, ""};
}

aq::ParamInfo param(const char* name, aq_param_type type, double def, double min, double max) {
  aq::ParamInfo info;
  info.name = name;
  info.type = type;
  info.default_value[0] = def;
  info.min_value = min;
  info.max_value = max;
  return info;
}

// scene -> gbuffer -> blur -> tint, plus a reader: enough port and parameter kinds for every
// check. Built as data, the way the plugin loader would fill it.
aq::Registry fake_registry() {
  aq::Registry registry;
  std::string why;

  aq::NodeType scene;
  scene.name = "scene";
  scene.outputs = {port("scene", AQ_PORT_SCENE)};
  aq::ParamInfo preset = param("preset", AQ_PARAM_ENUM, 0, 0, 0);
  preset.enum_values = {"underwater", "empty"};
  scene.params = {preset, param("seed", AQ_PARAM_INT, 7, 0, 1000)};
  EXPECT_TRUE(registry.add(scene, &why)) << why;

  aq::NodeType gbuffer;
  gbuffer.name = "gbuffer";
  gbuffer.inputs = {port("scene", AQ_PORT_SCENE)};
  gbuffer.outputs = {port("albedo", AQ_PORT_IMAGE), port("depth", AQ_PORT_IMAGE)};
  EXPECT_TRUE(registry.add(gbuffer, &why)) << why;

  aq::NodeType blur;
  blur.name = "blur";
  blur.inputs = {port("image", AQ_PORT_IMAGE), port("depth", AQ_PORT_IMAGE, true)};
  blur.outputs = {port("image", AQ_PORT_IMAGE)};
  aq::ParamInfo method = param("method", AQ_PARAM_ENUM, 0, 0, 0);
  method.enum_values = {"gaussian", "strided"};
  blur.params = {param("sigma", AQ_PARAM_FLOAT, 3, 0, 50), method,
                 param("exact", AQ_PARAM_BOOL, 1, 0, 1)};
  EXPECT_TRUE(registry.add(blur, &why)) << why;

  aq::NodeType tint;
  tint.name = "tint";
  tint.inputs = {port("image", AQ_PORT_IMAGE)};
  tint.outputs = {port("image", AQ_PORT_IMAGE)};
  aq::ParamInfo color = param("color", AQ_PARAM_COLOR, 0, 0, 1);
  color.default_value[1] = 0.07;
  color.default_value[2] = 0.1;
  tint.params = {param("amount", AQ_PARAM_FLOAT, 0.75, 0, 1), color};
  EXPECT_TRUE(registry.add(tint, &why)) << why;

  aq::NodeType reader;
  reader.name = "read";
  reader.outputs = {port("image", AQ_PORT_IMAGE)};
  aq::ParamInfo path = param("path", AQ_PARAM_PATH, 0, 0, 0);
  aq::ParamInfo label = param("label", AQ_PARAM_STRING, 0, 0, 0);
  label.default_string = "plate";
  reader.params = {path, label, param("offset", AQ_PARAM_VEC3, 0, -10, 10)};
  EXPECT_TRUE(registry.add(reader, &why)) << why;
  return registry;
}

const aq::Registry& registry() {
  static const aq::Registry instance = fake_registry();
  return instance;
}

// A valid graph; tests splice mistakes into copies of it. Line numbers matter to the tests.
const char* const kValidGraph = R"({
  "aquarelle": 1,
  "settings": { "width": 320, "height": 240, "fps": 24, "frames": [1, 48], "precision": "half" },
  "nodes": {
    "scene": { "type": "scene", "params": { "preset": "underwater", "seed": 7 } },
    "gbuf": { "type": "gbuffer", "inputs": { "scene": "scene.scene" } },
    "blur": { "type": "blur", "params": { "sigma": 3.0 },
              "inputs": { "image": "gbuf.albedo", "depth": "gbuf.depth" } },
    "tint": { "type": "tint", "params": { "color": [0.0, 0.07, 0.1] },
              "inputs": { "image": "blur.image" } }
  },
  "output": "tint.image",
  "editor": { "positions": { "scene": [40, 120] } }
}
)";

aq::ReadResult read(const std::string& text) {
  return aq::read_graph_text(text, registry(), "graph.json");
}

// Replaces the first occurrence of `from` in the valid graph (which must be there).
std::string valid_graph_with(const std::string& from, const std::string& to) {
  std::string text = kValidGraph;
  const size_t at = text.find(from);
  EXPECT_NE(at, std::string::npos) << "test setup: '" << from << "' not in the graph";
  if (at != std::string::npos) text.replace(at, from.size(), to);
  return text;
}

std::string all_messages(const std::vector<aq::Problem>& problems) {
  return aq::format_problems(problems);
}

// The one problem a text gives; fails the test when there is not exactly one.
aq::Problem only_problem(const std::string& text) {
  const aq::ReadResult result = read(text);
  EXPECT_EQ(result.problems.size(), 1u) << all_messages(result.problems);
  return result.problems.empty() ? aq::Problem{} : result.problems.front();
}

bool contains(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}

// ---- Reading a valid graph ----------------------------------------------------------------

TEST(GraphRead, ValidGraphHasNoProblemsAndFillsTheModel) {
  const aq::ReadResult result = read(kValidGraph);
  ASSERT_TRUE(result.ok()) << all_messages(result.problems);
  const aq::Graph& graph = result.graph;
  EXPECT_EQ(graph.source_path, "graph.json");
  EXPECT_EQ(graph.settings.width, 320);
  EXPECT_EQ(graph.settings.height, 240);
  EXPECT_EQ(graph.settings.fps, 24.0);
  EXPECT_EQ(graph.settings.first_frame, 1);
  EXPECT_EQ(graph.settings.last_frame, 48);
  EXPECT_EQ(graph.settings.precision, "half");
  EXPECT_EQ(graph.settings.quality, "final");  // default
  ASSERT_EQ(graph.nodes.size(), 4u);
  EXPECT_EQ(graph.nodes.at("blur").type, "blur");
  EXPECT_EQ(graph.nodes.at("blur").params.at("sigma"), 3.0);
  EXPECT_EQ(graph.nodes.at("blur").inputs.at("depth"), (aq::PortRef{"gbuf", "depth"}));
  EXPECT_EQ(graph.nodes.at("scene").params.at("preset"), "underwater");
  ASSERT_TRUE(graph.output.has_value());
  EXPECT_EQ(*graph.output, (aq::PortRef{"tint", "image"}));
  EXPECT_EQ(graph.editor["positions"]["scene"][1], 120);
}

TEST(GraphRead, ParamDefaultsComeFromTheType) {
  const aq::ReadResult result = read(kValidGraph);
  ASSERT_TRUE(result.ok());
  const aq::NodeType* blur = registry().find("blur");
  const aq::Node& node = result.graph.nodes.at("blur");
  EXPECT_EQ(aq::param_value_or_default(node, *blur->param("sigma")), 3.0);  // as written
  EXPECT_EQ(aq::param_value_or_default(node, *blur->param("method")), "gaussian");
  EXPECT_EQ(aq::param_value_or_default(node, *blur->param("exact")), true);
  const aq::NodeType* tint = registry().find("tint");
  EXPECT_EQ(aq::param_value_or_default(result.graph.nodes.at("tint"), *tint->param("amount")),
            0.75);
  const aq::NodeType* reader = registry().find("read");
  aq::Node empty_reader;
  EXPECT_EQ(aq::param_value_or_default(empty_reader, *reader->param("label")), "plate");
  const nlohmann::json zero3 = nlohmann::json::array({0.0, 0.0, 0.0});
  EXPECT_EQ(aq::param_value_or_default(empty_reader, *reader->param("offset")), zero3);
  const aq::NodeType* scene = registry().find("scene");
  const nlohmann::json seed = aq::param_value_or_default(empty_reader, *scene->param("seed"));
  EXPECT_TRUE(seed.is_number_integer());
  EXPECT_EQ(seed, 7);
}

TEST(PortRefParse, SplitsAtTheLastDot) {
  EXPECT_EQ(aq::PortRef::parse("blur.image"), (aq::PortRef{"blur", "image"}));
  EXPECT_EQ(aq::PortRef::parse("a.b.c"), (aq::PortRef{"a.b", "c"}));
  EXPECT_FALSE(aq::PortRef::parse("blur").has_value());
  EXPECT_FALSE(aq::PortRef::parse(".image").has_value());
  EXPECT_FALSE(aq::PortRef::parse("blur.").has_value());
  EXPECT_FALSE(aq::PortRef::parse("").has_value());
  EXPECT_EQ((aq::PortRef{"blur", "image"}.str()), "blur.image");
}

// ---- One test per kind of problem ------------------------------------------------------

TEST(GraphProblems, MalformedJsonGivesLineAndColumn) {
  const aq::Problem problem = only_problem("{\n  \"aquarelle\": 1,\n  \"nodes\" {}\n}\n");
  EXPECT_EQ(problem.line, 3);
  EXPECT_EQ(problem.column, 11);  // the '{' where ':' was expected
  EXPECT_TRUE(contains(problem.message, "malformed JSON")) << problem.message;
  EXPECT_TRUE(contains(problem.message, "expected ':'")) << problem.message;
  EXPECT_FALSE(contains(problem.message, "[json.exception")) << problem.message;
  EXPECT_EQ(problem.file, "graph.json");
}

TEST(GraphProblems, EmptyAndTruncatedTextAreMalformed) {
  const aq::Problem empty = only_problem("");
  EXPECT_TRUE(contains(empty.message, "malformed JSON")) << empty.message;
  EXPECT_EQ(empty.line, 1);
  const aq::Problem truncated = only_problem("{\n  \"aquarelle\": 1,\n");
  EXPECT_EQ(truncated.line, 3);
  EXPECT_TRUE(contains(truncated.message, "end of input")) << truncated.message;
}

TEST(GraphProblems, NotAnObject) {
  const aq::Problem problem = only_problem("[1, 2]");
  EXPECT_TRUE(contains(problem.message, "not an array")) << problem.message;
}

TEST(GraphProblems, MissingVersionIsReportedWithTheRest) {
  const aq::ReadResult result = read(valid_graph_with("\"aquarelle\": 1,", ""));
  ASSERT_EQ(result.problems.size(), 1u) << all_messages(result.problems);
  EXPECT_TRUE(contains(result.problems[0].message, "no \"aquarelle\" key"));
  EXPECT_EQ(result.problems[0].line, 1);
}

TEST(GraphProblems, UnsupportedVersionStopsReading) {
  // A version-2 file might be laid out differently: only the version is reported.
  const std::string text =
      valid_graph_with("\"aquarelle\": 1,", "\"aquarelle\": 2,\n  \"layers\": [],");
  const aq::ReadResult result = read(text);
  ASSERT_GE(result.problems.size(), 1u);
  bool found = false;
  for (const aq::Problem& problem : result.problems) {
    if (contains(problem.message, "unsupported version 2")) {
      found = true;
      EXPECT_EQ(problem.line, 2);
      EXPECT_EQ(problem.column, 3);
      EXPECT_EQ(problem.pointer, "/aquarelle");
    }
  }
  EXPECT_TRUE(found) << all_messages(result.problems);
  const aq::Problem string_version =
      only_problem(valid_graph_with("\"aquarelle\": 1,", "\"aquarelle\": \"1\","));
  EXPECT_TRUE(contains(string_version.message, "unsupported version \"1\""));
}

TEST(GraphProblems, UnknownNodeTypeListsInstalledTypesAndSuggests) {
  const aq::Problem problem =
      only_problem(valid_graph_with("\"type\": \"blur\"", "\"type\": \"blurr\""));
  EXPECT_EQ(problem.node, "blur");
  EXPECT_EQ(problem.pointer, "/nodes/blur/type");
  EXPECT_EQ(problem.line, 7);
  EXPECT_EQ(problem.column, 15);
  EXPECT_TRUE(contains(problem.message, "unknown node type 'blurr'")) << problem.message;
  EXPECT_TRUE(contains(problem.message, "did you mean 'blur'?")) << problem.message;
  EXPECT_TRUE(contains(problem.message, "installed types: blur, gbuffer, read, scene, tint"))
      << problem.message;
}

TEST(GraphProblems, UnknownInputPort) {
  const aq::Problem problem =
      only_problem(valid_graph_with("\"depth\": \"gbuf.depth\"", "\"dpeth\": \"gbuf.depth\""));
  EXPECT_EQ(problem.node, "blur");
  EXPECT_EQ(problem.field, "dpeth");
  EXPECT_EQ(problem.pointer, "/nodes/blur/inputs/dpeth");
  EXPECT_EQ(problem.line, 8);
  EXPECT_TRUE(contains(problem.message, "unknown input port 'dpeth'")) << problem.message;
  EXPECT_TRUE(contains(problem.message, "did you mean 'depth'?")) << problem.message;
  EXPECT_TRUE(contains(problem.message, "its inputs: image, depth")) << problem.message;
}

TEST(GraphProblems, UnknownParameter) {
  const aq::Problem problem = only_problem(valid_graph_with("\"sigma\": 3.0", "\"sigmaa\": 3.0"));
  EXPECT_EQ(problem.node, "blur");
  EXPECT_EQ(problem.field, "sigmaa");
  EXPECT_EQ(problem.line, 7);
  EXPECT_TRUE(contains(problem.message, "unknown parameter 'sigmaa' of node type 'blur'"))
      << problem.message;
  EXPECT_TRUE(contains(problem.message, "did you mean 'sigma'?")) << problem.message;
  EXPECT_TRUE(contains(problem.message, "its parameters: sigma, method, exact")) << problem.message;
}

TEST(GraphProblems, MissingRequiredInputPointsAtTheNode) {
  const aq::Problem problem =
      only_problem(valid_graph_with("\"inputs\": { \"image\": \"blur.image\" }", "\"inputs\": {}"));
  EXPECT_EQ(problem.node, "tint");
  EXPECT_EQ(problem.field, "image");
  EXPECT_EQ(problem.pointer, "/nodes/tint/inputs/image");
  EXPECT_EQ(problem.line, 10);  // where "inputs" is: the place to add it
  EXPECT_TRUE(contains(problem.message, "required input 'image' (image) is not connected"))
      << problem.message;
  // An optional input may stay unconnected.
  EXPECT_TRUE(read(valid_graph_with(", \"depth\": \"gbuf.depth\"", "")).ok());
}

TEST(GraphProblems, MalformedSourceIsReportedOnce) {
  const aq::Problem no_dot =
      only_problem(valid_graph_with("\"image\": \"blur.image\"", "\"image\": \"blur\""));
  EXPECT_EQ(no_dot.node, "tint");
  EXPECT_EQ(no_dot.field, "image");
  EXPECT_EQ(no_dot.line, 10);
  EXPECT_TRUE(
      contains(no_dot.message, "source 'blur' must be a string \"<node id>.<output port>\""))
      << no_dot.message;
  const aq::Problem number =
      only_problem(valid_graph_with("\"image\": \"blur.image\"", "\"image\": 4"));
  EXPECT_TRUE(contains(number.message, "source an integer must be")) << number.message;
}

TEST(GraphProblems, SourceNodeMissing) {
  const aq::Problem problem =
      only_problem(valid_graph_with("\"image\": \"blur.image\"", "\"image\": \"blurs.image\""));
  EXPECT_EQ(problem.node, "tint");
  EXPECT_EQ(problem.field, "image");
  EXPECT_EQ(problem.line, 10);
  EXPECT_TRUE(contains(problem.message, "names node 'blurs', which is not in the graph"))
      << problem.message;
  EXPECT_TRUE(contains(problem.message, "did you mean 'blur'?")) << problem.message;
}

TEST(GraphProblems, SourcePortMissing) {
  const aq::Problem problem = only_problem(valid_graph_with("\"gbuf.albedo\"", "\"gbuf.colour\""));
  EXPECT_EQ(problem.node, "blur");
  EXPECT_EQ(problem.field, "image");
  EXPECT_EQ(problem.line, 8);
  EXPECT_TRUE(contains(problem.message, "node 'gbuf' (type 'gbuffer') has no output 'colour'"))
      << problem.message;
  EXPECT_TRUE(contains(problem.message, "its outputs: albedo, depth")) << problem.message;
}

TEST(GraphProblems, PortTypeMismatch) {
  const aq::Problem problem = only_problem(valid_graph_with("\"gbuf.albedo\"", "\"scene.scene\""));
  EXPECT_EQ(problem.node, "blur");
  EXPECT_EQ(problem.field, "image");
  EXPECT_EQ(problem.line, 8);
  EXPECT_TRUE(contains(problem.message, "input 'image' takes image but 'scene.scene' gives scene"))
      << problem.message;
}

TEST(GraphProblems, CycleNamesItsNodesInDataFlowOrder) {
  const std::string text = R"({
  "aquarelle": 1,
  "nodes": {
    "x": { "type": "tint", "inputs": { "image": "z.image" } },
    "y": { "type": "tint", "inputs": { "image": "x.image" } },
    "z": { "type": "tint", "inputs": { "image": "y.image" } }
  },
  "output": "z.image"
})";
  const aq::Problem problem = only_problem(text);
  EXPECT_TRUE(contains(problem.message, "cycle: 'x' -> 'y' -> 'z' -> 'x'")) << problem.message;
  EXPECT_FALSE(problem.node.empty());
  EXPECT_EQ(problem.field, "image");
  EXPECT_GE(problem.line, 4);
  EXPECT_LE(problem.line, 6);
}

TEST(GraphProblems, SelfLoopIsACycle) {
  const std::string text = R"({
  "aquarelle": 1,
  "nodes": {
    "r": { "type": "read" },
    "loop": { "type": "blur", "inputs": { "image": "r.image", "depth": "loop.image" } }
  },
  "output": "loop.image"
})";
  const aq::Problem problem = only_problem(text);
  EXPECT_EQ(problem.node, "loop");
  EXPECT_EQ(problem.field, "depth");
  EXPECT_EQ(problem.line, 5);
  EXPECT_TRUE(contains(problem.message, "node 'loop' feeds itself through input 'depth'"))
      << problem.message;
}

TEST(GraphProblems, ParameterOfTheWrongType) {
  struct Case {
    const char* from;
    const char* to;
    const char* node;
    const char* field;
    const char* expected;
  };
  const Case cases[] = {
      {"\"sigma\": 3.0", "\"sigma\": \"3\"", "blur", "sigma",
       "expected value (a number), got a string \"3\""},
      {"\"sigma\": 3.0", "\"exact\": 1", "blur", "exact",
       "expected true or false, got an integer 1"},
      {"\"sigma\": 3.0", "\"method\": 1", "blur", "method",
       "expected one of gaussian, strided (a string)"},
      {"\"seed\": 7", "\"seed\": 7.5", "scene", "seed", "expected an integer, got 7.5"},
      {"\"seed\": 7", "\"seed\": true", "scene", "seed", "(an integer), got a boolean true"},
      {"[0.0, 0.07, 0.1]", "[0.0, 0.07]", "tint", "color",
       "expected an array of 3 numbers [r, g, b], got an array of 2 elements"},
      {"[0.0, 0.07, 0.1]", "[0.0, \"g\", 0.1]", "tint", "color", "expected component g (a number)"},
      {"[0.0, 0.07, 0.1]", "\"teal\"", "tint", "color", "expected an array of 3 numbers"},
      {"\"preset\": \"underwater\"", "\"preset\": \"underwter\"", "scene", "preset",
       "'underwter' is not one of underwater, empty (did you mean 'underwater'?)"},
  };
  for (const Case& c : cases) {
    const aq::Problem problem = only_problem(valid_graph_with(c.from, c.to));
    EXPECT_EQ(problem.node, c.node) << c.to;
    EXPECT_EQ(problem.field, c.field) << c.to;
    EXPECT_TRUE(contains(problem.message, c.expected)) << c.to << " -> " << problem.message;
    EXPECT_GT(problem.line, 0) << c.to;
  }
}

TEST(GraphProblems, ParameterOutOfRange) {
  const aq::Problem sigma = only_problem(valid_graph_with("\"sigma\": 3.0", "\"sigma\": 51"));
  EXPECT_EQ(sigma.line, 7);
  EXPECT_TRUE(contains(sigma.message, "float: value 51 is outside the range [0, 50]"))
      << sigma.message;
  const aq::Problem seed = only_problem(valid_graph_with("\"seed\": 7", "\"seed\": -1"));
  EXPECT_TRUE(contains(seed.message, "value -1 is outside the range [0, 1000]")) << seed.message;
  const aq::Problem color = only_problem(valid_graph_with("[0.0, 0.07, 0.1]", "[0.0, 0.07, 1.5]"));
  EXPECT_TRUE(contains(color.message, "component b 1.5 is outside the range [0, 1]"))
      << color.message;
  // The range is inclusive.
  EXPECT_TRUE(read(valid_graph_with("\"sigma\": 3.0", "\"sigma\": 50")).ok());
  EXPECT_TRUE(read(valid_graph_with("\"sigma\": 3.0", "\"sigma\": 0")).ok());
}

TEST(GraphProblems, HugeNumbersAreProblemsNotCrashes) {
  const aq::Problem overflow = only_problem(valid_graph_with("\"sigma\": 3.0", "\"sigma\": 1e400"));
  EXPECT_EQ(overflow.line, 7);
  EXPECT_EQ(overflow.column, 52);  // where the number starts
  EXPECT_TRUE(contains(overflow.message, "number 1e400 is too large")) << overflow.message;

  const aq::Problem width =
      only_problem(valid_graph_with("\"width\": 320", "\"width\": 99999999999"));
  EXPECT_EQ(width.field, "width");
  EXPECT_TRUE(contains(width.message, "width 99999999999 is too large")) << width.message;

  const aq::Problem seed =
      only_problem(valid_graph_with("\"seed\": 7", "\"seed\": 123456789012345678901234567890"));
  EXPECT_TRUE(contains(seed.message, "outside the range")) << seed.message;
}

TEST(GraphProblems, BadOutput) {
  struct Case {
    const char* to;
    const char* expected;
  };
  const Case cases[] = {
      {"", "no \"output\""},
      {"\"output\": \"tint\",", "output 'tint' must be a string \"<node id>.<output port>\""},
      {"\"output\": 3,", "output an integer must be"},
      {"\"output\": \"tnit.image\",",
       "names node 'tnit', which is not in the graph (did you mean 'tint'?)"},
      {"\"output\": \"gbuf.normal\",", "node 'gbuf' (type 'gbuffer') has no output 'normal'"},
      {"\"output\": \"scene.scene\",", "'scene.scene' is a scene; only an image can be rendered"},
  };
  for (const Case& c : cases) {
    const aq::Problem problem = only_problem(valid_graph_with("\"output\": \"tint.image\",", c.to));
    EXPECT_TRUE(contains(problem.message, c.expected)) << c.to << " -> " << problem.message;
    EXPECT_EQ(problem.pointer, "/output") << c.to;
    EXPECT_EQ(problem.line, *c.to == '\0' ? 1 : 12) << c.to;
  }
}

TEST(GraphProblems, BadSettings) {
  const std::string settings =
      R"("settings": { "width": 0, "height": 20000, "fps": 0, "frames": [5, 1],
    "precision": "double", "quality": "best", "colour": "srgb" },)";
  const aq::ReadResult result = read(valid_graph_with(
      R"("settings": { "width": 320, "height": 240, "fps": 24, "frames": [1, 48], "precision": "half" },)",
      settings));
  const std::string all = all_messages(result.problems);
  ASSERT_EQ(result.problems.size(), 7u) << all;
  EXPECT_TRUE(contains(
      all,
      "graph.json:3:17: setting 'width': width 0 must be a whole number of pixels in 1..16384"))
      << all;
  EXPECT_TRUE(contains(all, "setting 'height': height 20000 must be")) << all;
  EXPECT_TRUE(contains(all, "setting 'fps': fps 0 must be a positive number")) << all;
  EXPECT_TRUE(contains(
      all, "setting 'frames': frames [5, 1]: the first frame must not come after the last"))
      << all;
  EXPECT_TRUE(contains(
      all, "graph.json:4:5: setting 'precision': precision 'double' must be 'half' or 'float'"))
      << all;
  EXPECT_TRUE(contains(all, "setting 'quality': quality 'best' must be")) << all;
  EXPECT_TRUE(contains(all, "setting 'colour': unknown setting 'colour'")) << all;

  const aq::ReadResult wrong_types = read(
      valid_graph_with("\"width\": 320, \"height\": 240, \"fps\": 24, \"frames\": [1, 48]",
                       "\"width\": \"320\", \"height\": 240.0, \"fps\": \"24\", \"frames\": [1]"));
  const std::string types = all_messages(wrong_types.problems);
  ASSERT_EQ(wrong_types.problems.size(), 4u) << types;
  EXPECT_TRUE(contains(types, "width must be an integer, not a string")) << types;
  EXPECT_TRUE(contains(types, "height must be an integer, not a number")) << types;
  EXPECT_TRUE(contains(types, "fps must be a number, not a string")) << types;
  EXPECT_TRUE(contains(types, "frames must be [first, last]")) << types;
}

TEST(GraphProblems, UnknownKeysAreCaughtButTheEditorIsFree) {
  const aq::ReadResult result = read(valid_graph_with(
      "\"output\": \"tint.image\",", "\"outptu\": \"x\",\n  \"output\": \"tint.image\","));
  ASSERT_EQ(result.problems.size(), 1u) << all_messages(result.problems);
  EXPECT_TRUE(contains(result.problems[0].message, "unknown key 'outptu'"));
  EXPECT_EQ(result.problems[0].line, 12);

  const aq::Problem in_node = only_problem(valid_graph_with(
      "\"gbuf\": { \"type\": \"gbuffer\",", "\"gbuf\": { \"type\": \"gbuffer\", \"param\": {},"));
  EXPECT_EQ(in_node.node, "gbuf");
  EXPECT_TRUE(contains(in_node.message, "unknown key 'param' in a node")) << in_node.message;

  // Anything goes inside "editor".
  EXPECT_TRUE(
      read(valid_graph_with("\"positions\"", "\"zoom\": 2, \"notes\": [\"x\"], \"positions\""))
          .ok());
  const aq::Problem editor_not_object = only_problem(
      valid_graph_with("\"editor\": { \"positions\": { \"scene\": [40, 120] } }", "\"editor\": 3"));
  EXPECT_TRUE(contains(editor_not_object.message, "\"editor\" must be an object"));
}

TEST(GraphProblems, DuplicateKeysAreReportedWithBothPlaces) {
  const aq::ReadResult result =
      read(valid_graph_with("\"sigma\": 3.0", "\"sigma\": 3.0, \"sigma\": 4.0"));
  ASSERT_EQ(result.problems.size(), 1u) << all_messages(result.problems);
  const aq::Problem& problem = result.problems[0];
  EXPECT_EQ(problem.node, "blur");
  EXPECT_EQ(problem.field, "sigma");
  EXPECT_EQ(problem.line, 7);
  EXPECT_EQ(problem.column, 57);  // the second one
  EXPECT_TRUE(contains(problem.message, "key 'sigma' appears twice (first at line 7, column 43)"))
      << problem.message;

  const aq::ReadResult nodes =
      read(valid_graph_with("\"gbuf\": {", "\"tint\": { \"type\": \"read\" },\n    \"gbuf\": {"));
  bool found = false;
  for (const aq::Problem& p : nodes.problems) {
    found |= contains(p.message, "key 'tint' appears twice") && p.node == "tint" && p.line == 10 &&
             contains(p.message, "(first at line 6, column 5)");
  }
  EXPECT_TRUE(found) << all_messages(nodes.problems);
}

TEST(GraphProblems, NodeIdsWithOddCharacters) {
  for (const std::string id : {"a.b", "1abc", "bad id", "-x", "é", "a/b"}) {
    const std::string text =
        R"({ "aquarelle": 1, "nodes": { ")" + id +
        R"(": { "type": "read" }, "ok": { "type": "read" } }, "output": "ok.image" })";
    const aq::Problem problem = only_problem(text);
    EXPECT_EQ(problem.node, id);
    EXPECT_TRUE(contains(problem.message, "node id '" + id + "' is not allowed"))
        << problem.message;
    EXPECT_EQ(problem.line, 1);
    EXPECT_EQ(problem.column, 30) << id;
  }
  for (const std::string id : {"a", "_a", "A-b_9", "scene2"}) {
    const std::string text = R"({ "aquarelle": 1, "nodes": { ")" + id +
                             R"(": { "type": "read" } }, "output": ")" + id + R"(.image" })";
    EXPECT_TRUE(read(text).ok()) << id << ": " << all_messages(read(text).problems);
  }
}

TEST(GraphProblems, DeepNestingIsRefusedWithoutCrashing) {
  const std::string deep = std::string(100000, '[') + std::string(100000, ']');
  const aq::Problem problem = only_problem(deep);
  EXPECT_TRUE(contains(problem.message, "nest deeper than 64 levels")) << problem.message;
  EXPECT_EQ(problem.line, 1);
  EXPECT_EQ(problem.column, 65);

  // Also inside the editor's free-form part, and unterminated.
  const std::string editor_deep =
      valid_graph_with("\"positions\"", "\"deep\": " + std::string(70, '[') + ", \"positions\"");
  const aq::Problem unterminated = only_problem(editor_deep);
  EXPECT_TRUE(contains(unterminated.message, "nest deeper")) << unterminated.message;
  EXPECT_EQ(unterminated.line, 13);

  // Brackets inside strings do not count.
  EXPECT_TRUE(read(valid_graph_with("\"positions\"",
                                    "\"text\": \"" + std::string(500, '[') + "\", \"positions\""))
                  .ok());
}

TEST(GraphProblems, OddBytesAreMalformedJson) {
  // Invalid UTF-8 inside a string, a NUL byte, a lone surrogate escape.
  const aq::Problem utf8 = only_problem(valid_graph_with("\"gbuf\": {",
                                                         "\"g\xFF"
                                                         "buf\": {"));
  EXPECT_TRUE(contains(utf8.message, "malformed JSON")) << utf8.message;
  EXPECT_EQ(utf8.line, 6);
  const aq::Problem nul =
      only_problem(valid_graph_with("\"tint.image\"", std::string("\"tint\0.image\"", 13)));
  EXPECT_TRUE(contains(nul.message, "malformed JSON")) << nul.message;
  EXPECT_EQ(nul.line, 12);
  const aq::Problem surrogate =
      only_problem(valid_graph_with("\"tint.image\"", "\"tint\\ud800.image\""));
  EXPECT_TRUE(contains(surrogate.message, "malformed JSON")) << surrogate.message;
  // Escaped keys are matched as nlohmann decodes them: "\u0073igma" is "sigma".
  const aq::Problem escaped =
      only_problem(valid_graph_with("\"sigma\": 3.0", "\"\\u0073igma\": 300"));
  EXPECT_EQ(escaped.field, "sigma");
  EXPECT_EQ(escaped.line, 7);
  EXPECT_EQ(escaped.column, 43);
}

TEST(GraphProblems, ColumnsCountCharactersNotBytes) {
  const aq::Problem problem = only_problem(
      "{ \"aquarelle\": 1, \"nodes\": { \"r\": { \"type\": \"read\", \"params\": { \"label\": "
      "\"\xC3\xA9t\xC3\xA9\", \"path\": 5 } } }, \"output\": \"r.image\" }");
  EXPECT_EQ(problem.field, "path");
  EXPECT_EQ(problem.column, 81);  // 83 if bytes were counted
}

TEST(GraphProblems, EveryProblemAtOnceInFileOrder) {
  const std::string text = R"({
  "aquarelle": 1,
  "settings": { "width": -5 },
  "nodes": {
    "scene": { "type": "scen" },
    "gbuf": { "type": "gbuffer", "inputs": { "scene": "scene.scene" } },
    "blur": { "type": "blur", "params": { "sigma": "wide", "sharp": true },
              "inputs": { "image": "gbuf.depth", "depth": "nowhere.image" } },
    "tint": { "type": "tint", "inputs": { "colour": "blur.image" } }
  },
  "output": "tint.img"
})";
  const aq::ReadResult result = read(text);
  const std::string all = all_messages(result.problems);
  ASSERT_EQ(result.problems.size(), 8u) << all;
  const int expected_lines[] = {3, 5, 7, 7, 8, 9, 9, 11};
  for (size_t i = 0; i < result.problems.size(); ++i) {
    EXPECT_EQ(result.problems[i].line, expected_lines[i]) << all;
  }
  EXPECT_TRUE(contains(all,
                       "graph.json:7:43: node 'blur', parameter 'sigma': float: expected value (a "
                       "number), got a string \"wide\""))
      << all;
  EXPECT_TRUE(contains(all, "node 'blur', parameter 'sharp': unknown parameter")) << all;
  EXPECT_TRUE(contains(all, "node 'blur', input 'depth': source 'nowhere.image'")) << all;
  EXPECT_TRUE(contains(all, "node 'tint', input 'colour': unknown input port")) << all;
  EXPECT_TRUE(contains(all, "node 'tint', input 'image': required input 'image'")) << all;
  EXPECT_TRUE(contains(all, "node 'scene': unknown node type 'scen'")) << all;
  EXPECT_TRUE(contains(all, "has no output 'img'")) << all;
  EXPECT_FALSE(result.ok());
}

// ---- Problems of models validated in memory and their formatting --------------------

TEST(GraphValidate, ModelProblemsHaveOnlyPointers) {
  aq::ReadResult result = read(kValidGraph);
  ASSERT_TRUE(result.ok());
  aq::Graph graph = result.graph;
  graph.nodes.at("blur").params["sigma"] = std::nan("");
  graph.nodes.at("blur").inputs.erase("image");
  graph.settings.precision = "quad";
  graph.version = 3;
  const std::vector<aq::Problem> problems = aq::validate_graph(graph, registry());
  const std::string all = all_messages(problems);
  ASSERT_EQ(problems.size(), 4u) << all;
  EXPECT_TRUE(contains(all, "/aquarelle: unsupported version 3")) << all;
  EXPECT_TRUE(contains(all,
                       "/nodes/blur/params/sigma: node 'blur', parameter 'sigma': float: value "
                       "must be a finite number"))
      << all;
  EXPECT_TRUE(contains(all, "/nodes/blur/inputs/image: node 'blur', input 'image': required input"))
      << all;
  EXPECT_TRUE(contains(all, "/settings/precision: setting 'precision'")) << all;
  for (const aq::Problem& problem : problems) EXPECT_EQ(problem.line, 0);
}

TEST(GraphValidate, FormatProblemOmitsEmptyParts) {
  aq::Problem problem;
  problem.message = "broken";
  EXPECT_EQ(aq::format_problem(problem), "broken");
  problem.file = "g.json";
  EXPECT_EQ(aq::format_problem(problem), "g.json: broken");
  problem.line = 12;
  problem.column = 7;
  EXPECT_EQ(aq::format_problem(problem), "g.json:12:7: broken");
  problem.node = "blur";
  EXPECT_EQ(aq::format_problem(problem), "g.json:12:7: node 'blur': broken");
  problem.field = "sigma";
  problem.pointer = "/nodes/blur/params/sigma";
  EXPECT_EQ(aq::format_problem(problem), "g.json:12:7: node 'blur', parameter 'sigma': broken");
  problem.file.clear();
  EXPECT_EQ(aq::format_problem(problem), "12:7: node 'blur', parameter 'sigma': broken");
  problem.line = 0;
  EXPECT_EQ(aq::format_problem(problem),
            "/nodes/blur/params/sigma: node 'blur', parameter 'sigma': broken");
  EXPECT_EQ(aq::format_problems({problem, problem}),
            aq::format_problem(problem) + "\n" + aq::format_problem(problem));
  EXPECT_EQ(aq::format_problems({}), "");
}

// ---- Writing --------------------------------------------------------------------------

TEST(GraphWrite, CanonicalText) {
  // Keys in an odd order, odd spacing, a node without params: the output is canonical.
  const std::string messy = R"({"editor":{"z":1,"a":[1,2]},"output":"t.image","nodes":{
"t":{"inputs":{"image":"r.image"},"params":{"color":[0, 0.07,0.1],"amount":1},"type":"tint"},
"r":{"type":"read","params":{"path":"plate.exr"}}},"aquarelle":1,
"settings":{"quality":"draft","fps":23.976,"width":64,"height":32}})";
  const aq::ReadResult result = read(messy);
  ASSERT_TRUE(result.ok()) << all_messages(result.problems);
  const std::string expected = R"({
  "aquarelle": 1,
  "settings": {
    "fps": 23.976,
    "frames": [1, 1],
    "height": 32,
    "precision": "half",
    "quality": "draft",
    "width": 64
  },
  "nodes": {
    "r": {
      "type": "read",
      "params": {
        "path": "plate.exr"
      }
    },
    "t": {
      "type": "tint",
      "params": {
        "amount": 1,
        "color": [0, 0.07, 0.1]
      },
      "inputs": {
        "image": "r.image"
      }
    }
  },
  "output": "t.image",
  "editor": {
    "a": [1, 2],
    "z": 1
  }
}
)";
  EXPECT_EQ(aq::write_graph_text(result.graph), expected);
}

TEST(GraphWrite, ParamsAreWrittenExactlyAsStored) {
  aq::Graph graph;
  aq::Node node;
  node.type = "tint";
  node.params["amount"] = 1.0;  // a float stays a float
  node.params["color"] = nlohmann::json::array({0, 0.5, 1e-7});
  node.params["label"] = "a \"quoted\" \\ name\n";
  graph.nodes["n"] = node;
  const std::string text = aq::write_graph_text(graph);
  EXPECT_TRUE(contains(text, "\"amount\": 1.0")) << text;
  EXPECT_TRUE(contains(text, "\"color\": [0, 0.5, 1e-07]")) << text;
  EXPECT_TRUE(contains(text, R"("label": "a \"quoted\" \\ name\n")")) << text;
  EXPECT_TRUE(contains(text, "\"fps\": 24,")) << text;
  EXPECT_FALSE(contains(text, "\"output\"")) << text;  // none set
  EXPECT_FALSE(contains(text, "\"editor\"")) << text;  // empty
  EXPECT_EQ(text.back(), '\n');
  const aq::ReadResult again = read(text);
  EXPECT_EQ(again.graph.nodes.at("n").params, node.params);
}

TEST(GraphWrite, ReadWriteReadIsIdentical) {
  const aq::ReadResult first = read(kValidGraph);
  ASSERT_TRUE(first.ok());
  const std::string written = aq::write_graph_text(first.graph);
  const aq::ReadResult second = read(written);
  ASSERT_TRUE(second.ok()) << all_messages(second.problems) << written;
  EXPECT_EQ(aq::write_graph_text(second.graph), written);
  // The models agree field by field, not only through the writer.
  const aq::Graph& a = first.graph;
  const aq::Graph& b = second.graph;
  EXPECT_EQ(a.version, b.version);
  EXPECT_EQ(a.settings.width, b.settings.width);
  EXPECT_EQ(a.settings.fps, b.settings.fps);
  EXPECT_EQ(a.settings.first_frame, b.settings.first_frame);
  EXPECT_EQ(a.settings.last_frame, b.settings.last_frame);
  EXPECT_EQ(a.settings.precision, b.settings.precision);
  EXPECT_EQ(a.settings.quality, b.settings.quality);
  EXPECT_EQ(a.output, b.output);
  EXPECT_EQ(a.editor, b.editor);
  ASSERT_EQ(a.nodes.size(), b.nodes.size());
  for (const auto& [id, node] : a.nodes) {
    const aq::Node& other = b.nodes.at(id);
    EXPECT_EQ(node.type, other.type) << id;
    EXPECT_EQ(node.params, other.params) << id;
    EXPECT_EQ(node.inputs, other.inputs) << id;
  }
  // Float-looking values keep their float-ness, integers stay integers.
  EXPECT_TRUE(b.nodes.at("blur").params.at("sigma").is_number_float());
  EXPECT_TRUE(b.nodes.at("scene").params.at("seed").is_number_integer());
}

TEST(GraphWrite, OddFpsRoundTripsExactly) {
  aq::Graph graph;
  graph.settings.fps = 30000.0 / 1001.0;
  const aq::ReadResult again = read(aq::write_graph_text(graph));
  EXPECT_EQ(again.graph.settings.fps, graph.settings.fps);
}

// ---- Saving ----------------------------------------------------------------------------

class GraphSave : public ::testing::Test {
 protected:
  void SetUp() override {
    directory_ = fs::temp_directory_path() /
                 ("aquarelle_graph_save_" + std::to_string(::getpid()) + "_" +
                  ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(directory_);
    fs::create_directories(directory_);
  }
  void TearDown() override {
    std::error_code ignored;
    fs::permissions(directory_, fs::perms::owner_all, fs::perm_options::add, ignored);
    fs::remove_all(directory_, ignored);
  }
  std::vector<std::string> files() const {
    std::vector<std::string> names;
    for (const auto& entry : fs::directory_iterator(directory_)) {
      names.push_back(entry.path().filename().string());
    }
    std::sort(names.begin(), names.end());
    return names;
  }
  static std::string slurp(const fs::path& path) {
    std::ifstream in(path, std::ios::binary);
    std::ostringstream text;
    text << in.rdbuf();
    return text.str();
  }

  fs::path directory_;
};

TEST_F(GraphSave, WritesCanonicalTextAndLeavesNoTemporaryFile) {
  const aq::ReadResult result = read(kValidGraph);
  ASSERT_TRUE(result.ok());
  const fs::path path = directory_ / "graph.json";
  const aq::Status saved = aq::save_graph_file(result.graph, path.string());
  ASSERT_TRUE(saved.ok()) << saved.message();
  EXPECT_EQ(slurp(path), aq::write_graph_text(result.graph));
  EXPECT_EQ(files(), std::vector<std::string>{"graph.json"});

  const aq::ReadResult loaded = aq::read_graph_file(path.string(), registry());
  ASSERT_TRUE(loaded.ok()) << all_messages(loaded.problems);
  EXPECT_EQ(loaded.graph.source_path, path.string());
  EXPECT_EQ(aq::write_graph_text(loaded.graph), aq::write_graph_text(result.graph));
}

TEST_F(GraphSave, ReplacesAnExistingFileKeepingItsPermissions) {
  const fs::path path = directory_ / "graph.json";
  { std::ofstream(path) << "old contents"; }
  ::chmod(path.c_str(), 0640);
  aq::Graph graph;
  ASSERT_TRUE(aq::save_graph_file(graph, path.string()).ok());
  EXPECT_EQ(slurp(path), aq::write_graph_text(graph));
  struct stat info {};
  ASSERT_EQ(::stat(path.c_str(), &info), 0);
  EXPECT_EQ(info.st_mode & 0777, 0640u);
  EXPECT_EQ(files(), std::vector<std::string>{"graph.json"});
}

TEST_F(GraphSave, SavesThroughASymbolicLinkKeepingTheLink) {
  const fs::path real = directory_ / "real.json";
  const fs::path link = directory_ / "link.json";
  { std::ofstream(real) << "old"; }
  fs::create_symlink(real, link);
  aq::Graph graph;
  ASSERT_TRUE(aq::save_graph_file(graph, link.string()).ok());
  EXPECT_TRUE(fs::is_symlink(link));
  EXPECT_EQ(slurp(real), aq::write_graph_text(graph));
  EXPECT_EQ(files(), (std::vector<std::string>{"link.json", "real.json"}));
}

TEST_F(GraphSave, FullDeviceGivesAnErrorNamingThePathAndTheReason) {
  if (!fs::exists("/dev/full")) GTEST_SKIP() << "no /dev/full here";
  const aq::Status saved = aq::save_graph_file(aq::Graph{}, "/dev/full");
  ASSERT_FALSE(saved.ok());
  EXPECT_TRUE(contains(saved.message(), "/dev/full")) << saved.message();
  EXPECT_TRUE(contains(saved.message(), "No space left on device")) << saved.message();
  EXPECT_TRUE(fs::is_character_file("/dev/full"));  // still the device, not replaced
}

TEST_F(GraphSave, MissingDirectoryGivesAnError) {
  const fs::path path = directory_ / "no" / "such" / "graph.json";
  const aq::Status saved = aq::save_graph_file(aq::Graph{}, path.string());
  ASSERT_FALSE(saved.ok());
  EXPECT_TRUE(contains(saved.message(), path.string())) << saved.message();
  EXPECT_TRUE(contains(saved.message(), "No such file or directory")) << saved.message();
  EXPECT_EQ(files(), std::vector<std::string>{});
}

TEST_F(GraphSave, DirectoryAsTargetGivesAnError) {
  const aq::Status saved = aq::save_graph_file(aq::Graph{}, directory_.string());
  ASSERT_FALSE(saved.ok());
  EXPECT_TRUE(contains(saved.message(), "is a directory")) << saved.message();
}

TEST_F(GraphSave, LocationNobodyCanWriteGivesAnError) {
  // /proc refuses new files even to root, so this runs where permissions cannot fail.
  if (!fs::exists("/proc/self")) GTEST_SKIP() << "no /proc here";
  const aq::Status saved = aq::save_graph_file(aq::Graph{}, "/proc/aquarelle_graph.json");
  ASSERT_FALSE(saved.ok());
  EXPECT_TRUE(contains(saved.message(), "'/proc/aquarelle_graph.json'")) << saved.message();
  EXPECT_TRUE(contains(saved.message(), "temporary file")) << saved.message();
}

TEST_F(GraphSave, UnwritableDirectoryGivesAnErrorAndKeepsTheOldFile) {
  if (::geteuid() == 0) GTEST_SKIP() << "root may write anywhere; permissions cannot fail";
  const fs::path path = directory_ / "graph.json";
  { std::ofstream(path) << "old"; }
  fs::permissions(directory_, fs::perms::owner_read | fs::perms::owner_exec);
  const aq::Status saved = aq::save_graph_file(aq::Graph{}, path.string());
  ASSERT_FALSE(saved.ok());
  EXPECT_TRUE(contains(saved.message(), path.string())) << saved.message();
  EXPECT_TRUE(contains(saved.message(), "Permission denied")) << saved.message();
  EXPECT_EQ(slurp(path), "old");
}

TEST_F(GraphSave, ReadingAMissingFileOrADirectoryIsAProblem) {
  const std::string missing = (directory_ / "missing.json").string();
  const aq::ReadResult result = aq::read_graph_file(missing, registry());
  ASSERT_EQ(result.problems.size(), 1u);
  EXPECT_EQ(result.problems[0].file, missing);
  EXPECT_TRUE(contains(aq::format_problem(result.problems[0]), missing + ": cannot read"))
      << aq::format_problem(result.problems[0]);
  EXPECT_TRUE(contains(result.problems[0].message, "No such file")) << result.problems[0].message;
  const aq::ReadResult directory = aq::read_graph_file(directory_.string(), registry());
  ASSERT_EQ(directory.problems.size(), 1u);
  EXPECT_TRUE(contains(directory.problems[0].message, "directory"));
}

// ---- Scale ----------------------------------------------------------------------------

// 10,000 nodes read and validate without a crash or a stall; the only problem is the limit
// on the nodes an output depends on (kMaxGraphNodes, issue 40).
TEST(GraphScale, TenThousandNodeChainValidates) {
  constexpr int kNodes = 10000;
  std::string text = "{\n  \"aquarelle\": 1,\n  \"nodes\": {\n    \"n0\": { \"type\": \"read\" }";
  for (int i = 1; i < kNodes; ++i) {
    text += ",\n    \"n" + std::to_string(i) +
            "\": { \"type\": \"tint\", \"params\": { \"amount\": 0.5 }, " +
            "\"inputs\": { \"image\": \"n" + std::to_string(i - 1) + ".image\" } }";
  }
  text += "\n  },\n  \"output\": \"n" + std::to_string(kNodes - 1) + ".image\"\n}\n";
  const aq::ReadResult result = read(text);
  ASSERT_EQ(result.problems.size(), 1u) << all_messages(result.problems);
  EXPECT_TRUE(contains(result.problems[0].message, "more than 1000 nodes"));
  EXPECT_EQ(result.graph.nodes.size(), static_cast<size_t>(kNodes));
  EXPECT_EQ(aq::validate_graph(result.graph, registry()).size(), 1u);
  const aq::ReadResult again = read(aq::write_graph_text(result.graph));
  EXPECT_EQ(again.problems.size(), 1u);

  // Close the chain into one 10,000-node cycle: found, named, no stack overflow.
  aq::Graph cyclic = result.graph;
  cyclic.nodes["n0"].type = "tint";
  cyclic.nodes["n0"].inputs["image"] = aq::PortRef{"n9999", "image"};
  const std::vector<aq::Problem> problems = aq::validate_graph(cyclic, registry());
  ASSERT_EQ(problems.size(), 2u);  // the cycle, and the node limit
  const aq::Problem& cycle = contains(problems[0].message, "cycle") ? problems[0] : problems[1];
  EXPECT_TRUE(contains(cycle.message, "cycle: 'n0' -> 'n1' -> 'n2'"))
      << cycle.message.substr(0, 200);
}

// ---- The malformed graph files in tests/data/graphs/invalid -----------------------------

// Mirrors the node types those files use (the built-in `read`, the tint, vignette and scene
// plugins), so the files can be checked without loading plugins; the command-line tests run
// the same files through `aquarelle validate` with the real plugins.
aq::Registry file_registry() {
  aq::Registry registry;
  std::string why;
  aq::NodeType reader;
  reader.name = "read";
  reader.outputs = {port("image", AQ_PORT_IMAGE)};
  reader.params = {param("path", AQ_PARAM_PATH, 0, 0, 0),
                   param("colorspace", AQ_PARAM_STRING, 0, 0, 0)};
  EXPECT_TRUE(registry.add(reader, &why)) << why;

  aq::NodeType tint;
  tint.name = "tint";
  tint.inputs = {port("image", AQ_PORT_IMAGE)};
  tint.outputs = {port("image", AQ_PORT_IMAGE)};
  tint.params = {param("amount", AQ_PARAM_FLOAT, 0.75, 0, 1),
                 param("tint", AQ_PARAM_COLOR, 0, 0, 1)};
  EXPECT_TRUE(registry.add(tint, &why)) << why;

  aq::NodeType vignette;
  vignette.name = "vignette";
  vignette.inputs = {port("image", AQ_PORT_IMAGE)};
  vignette.outputs = {port("image", AQ_PORT_IMAGE)};
  vignette.params = {param("radius", AQ_PARAM_FLOAT, 0.45, 0, 2),
                     param("strength", AQ_PARAM_FLOAT, 0.7, 0, 1),
                     param("softness", AQ_PARAM_FLOAT, 1, 0, 1)};
  EXPECT_TRUE(registry.add(vignette, &why)) << why;

  aq::NodeType scene;
  scene.name = "scene";
  scene.outputs = {port("scene", AQ_PORT_SCENE)};
  aq::ParamInfo preset = param("preset", AQ_PARAM_ENUM, 0, 0, 0);
  preset.enum_values = {"underwater", "plane_box", "pot", "cube", "double_plane", "file"};
  scene.params = {preset, param("path", AQ_PARAM_PATH, 0, 0, 0),
                  param("seed", AQ_PARAM_INT, 7, 0, 2147483647)};
  EXPECT_TRUE(registry.add(scene, &why)) << why;
  return registry;
}

std::string trim(const std::string& text) {
  const size_t first = text.find_first_not_of(' ');
  const size_t last = text.find_last_not_of(' ');
  return first == std::string::npos ? "" : text.substr(first, last - first + 1);
}

TEST(GraphFiles, TheValidGraphTheyBreakIsValid) {
  const aq::Registry registry = file_registry();
  const aq::ReadResult result =
      aq::read_graph_file(AQ_SOURCE_DIR "/tests/data/graphs/valid.json", registry);
  EXPECT_TRUE(result.ok()) << all_messages(result.problems);
}

TEST(GraphFiles, EachMalformedFileGivesItsOneProblemAtItsPlace) {
  const aq::Registry registry = file_registry();
  const fs::path folder = AQ_SOURCE_DIR "/tests/data/graphs/invalid";
  std::ifstream expectations(folder / "expected.txt");
  ASSERT_TRUE(expectations) << "cannot open " << (folder / "expected.txt");
  std::set<std::string> listed;
  std::string line;
  while (std::getline(expectations, line)) {
    if (line.empty() || line[0] == '#') continue;
    const size_t bar1 = line.find('|');
    const size_t bar2 = line.find('|', bar1 + 1);
    ASSERT_NE(bar2, std::string::npos) << "bad line in expected.txt: " << line;
    const std::string file = trim(line.substr(0, bar1));
    const std::string place = trim(line.substr(bar1 + 1, bar2 - bar1 - 1));
    const std::string expected = trim(line.substr(bar2 + 1));
    listed.insert(file);

    const std::string path = (folder / file).string();
    const aq::ReadResult result = aq::read_graph_file(path, registry);
    EXPECT_EQ(result.problems.size(), 1u) << file << ":\n" << all_messages(result.problems);
    if (result.problems.empty()) continue;
    const std::string formatted = aq::format_problem(result.problems[0]);
    EXPECT_EQ(formatted.rfind(path + ":" + place + ": ", 0), 0u)
        << file << ": expected at " << place << ", got\n"
        << formatted;
    EXPECT_TRUE(contains(formatted, expected)) << file << ": expected \"" << expected << "\", got\n"
                                               << formatted;
  }
  // Every file in the folder is listed, so none is silently left unchecked.
  for (const auto& entry : fs::directory_iterator(folder)) {
    if (entry.path().extension() == ".json") {
      EXPECT_EQ(listed.count(entry.path().filename().string()), 1u) << entry.path();
    }
  }
  EXPECT_GE(listed.size(), 40u);
}

}  // namespace
