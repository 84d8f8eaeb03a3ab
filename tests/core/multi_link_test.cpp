// Inputs that take several links (AQ_PORT_MULTI): a plugin may declare them on scene inputs
// only; graph files give them as arrays of sources, read in order, written back the same way
// (one link stays a plain string), and every link is checked like a single one; a plain port
// given an array is a located problem.
#include <gtest/gtest.h>

#include <aquarelle/core/graph_io.h>
#include <aquarelle/core/registry.h>

#include <string>

namespace {

aq::PortInfo port(const char* name, aq_port_type type, bool optional = false, bool multi = false) {
  aq::PortInfo info{name, type, optional, ""};
  info.multi = multi;
  return info;
}

const aq::Registry& registry() {
  static const aq::Registry instance = [] {
    aq::Registry registry;
    std::string why;
    aq::NodeType object;
    object.name = "object";
    object.outputs = {port("object", AQ_PORT_SCENE)};
    EXPECT_TRUE(registry.add(object, &why)) << why;
    aq::NodeType image;
    image.name = "noise";
    image.outputs = {port("image", AQ_PORT_IMAGE)};
    EXPECT_TRUE(registry.add(image, &why)) << why;
    aq::NodeType join;
    join.name = "scene_join";
    join.inputs = {port("objects", AQ_PORT_SCENE, true, true)};
    join.outputs = {port("scene", AQ_PORT_SCENE)};
    EXPECT_TRUE(registry.add(join, &why)) << why;
    aq::NodeType gbuffer;
    gbuffer.name = "gbuffer";
    gbuffer.inputs = {port("scene", AQ_PORT_SCENE)};
    gbuffer.outputs = {port("albedo", AQ_PORT_IMAGE)};
    EXPECT_TRUE(registry.add(gbuffer, &why)) << why;
    return registry;
  }();
  return instance;
}

std::string graph_text(const std::string& objects, const std::string& scene = "\"join.scene\"") {
  return R"({"aquarelle": 1, "nodes": {
    "a": {"type": "object"}, "b": {"type": "object"}, "c": {"type": "object"},
    "n": {"type": "noise"},
    "join": {"type": "scene_join", "inputs": {"objects": )" +
         objects + R"(}},
    "gbuf": {"type": "gbuffer", "inputs": {"scene": )" +
         scene + R"(}}},
  "output": "gbuf.albedo"})";
}

TEST(MultiLink, ArrayOfSourcesKeepsItsOrderAndRoundTrips) {
  auto read =
      aq::read_graph_text(graph_text(R"(["c.object", "a.object", "b.object"])"), registry());
  ASSERT_TRUE(read.ok()) << aq::format_problems(read.problems);
  const auto links = read.graph.nodes.at("join").inputs.links("objects");
  ASSERT_EQ(links.size(), 3u);
  EXPECT_EQ(links[0].node, "c");
  EXPECT_EQ(links[1].node, "a");
  EXPECT_EQ(links[2].node, "b");
  // Every link counts as a dependency (iteration visits them all).
  int visited = 0;
  for (const auto& [port, source] : read.graph.nodes.at("join").inputs)
    visited += port == "objects";
  EXPECT_EQ(visited, 3);

  const std::string written = aq::write_graph_text(read.graph);
  EXPECT_NE(written.find("\"c.object\",\n"), std::string::npos) << written;
  auto again = aq::read_graph_text(written, registry());
  ASSERT_TRUE(again.ok()) << aq::format_problems(again.problems);
  EXPECT_EQ(again.graph.nodes.at("join").inputs.links("objects"), links);
}

TEST(MultiLink, OneLinkIsWrittenAsAString) {
  auto read = aq::read_graph_text(graph_text(R"(["a.object"])"), registry());
  ASSERT_TRUE(read.ok()) << aq::format_problems(read.problems);
  EXPECT_NE(aq::write_graph_text(read.graph).find("\"objects\": \"a.object\""), std::string::npos);
  auto none = aq::read_graph_text(graph_text("[]"), registry());
  EXPECT_TRUE(none.ok()) << aq::format_problems(none.problems);
}

TEST(MultiLink, EachLinkIsCheckedAndLocated) {
  auto read = aq::read_graph_text(graph_text(R"(["a.object", "n.image", 7])"), registry());
  ASSERT_EQ(read.problems.size(), 2u) << aq::format_problems(read.problems);
  const std::string text = aq::format_problems(read.problems);
  EXPECT_NE(text.find("takes scene but 'n.image' gives image"), std::string::npos) << text;
  EXPECT_NE(text.find("source an integer must be a string"), std::string::npos) << text;
}

TEST(MultiLink, PlainPortRefusesAnArray) {
  auto read = aq::read_graph_text(graph_text("\"a.object\"", R"(["join.scene", "join.scene"])"),
                                  registry());
  ASSERT_EQ(read.problems.size(), 1u) << aq::format_problems(read.problems);
  EXPECT_EQ(read.problems[0].node, "gbuf");
  EXPECT_EQ(read.problems[0].field, "scene");
  EXPECT_NE(read.problems[0].message.find("takes one link, not 2"), std::string::npos);
  EXPECT_GT(read.problems[0].line, 0);
}

TEST(MultiLink, PluginsMayDeclareItOnSceneInputsOnly) {
  static const aq_port_desc scene_in[] = {
      {"objects", AQ_PORT_SCENE, AQ_PORT_OPTIONAL | AQ_PORT_MULTI, "objects"}};
  static const aq_port_desc image_in[] = {{"images", AQ_PORT_IMAGE, AQ_PORT_MULTI, "images"}};
  static const aq_port_desc out[] = {{"scene", AQ_PORT_SCENE, 0, "scene"}};
  aq_node_desc desc{};
  desc.struct_size = sizeof(aq_node_desc);
  desc.type_name = "joiner";
  desc.category = "Scene";
  desc.inputs = scene_in;
  desc.input_count = 1;
  desc.outputs = out;
  desc.output_count = 1;
  std::string why;
  aq::NodeType type = aq::node_type_from_desc(desc, "test.so", &why);
  EXPECT_EQ(type.name, "joiner") << why;
  ASSERT_EQ(type.inputs.size(), 1u);
  EXPECT_TRUE(type.inputs[0].multi);
  EXPECT_TRUE(type.has_multi_input());
  desc.inputs = image_in;
  type = aq::node_type_from_desc(desc, "test.so", &why);
  EXPECT_TRUE(type.name.empty());
  EXPECT_NE(why.find("only scene inputs may take several links"), std::string::npos) << why;
}

// A plugin built before `check` was appended (struct_size up to `pointwise`) still loads.
TEST(MultiLink, OlderNodeDescriptionsStillLoad) {
  static const aq_port_desc out[] = {{"scene", AQ_PORT_SCENE, 0, "scene"}};
  aq_node_desc desc{};
  desc.struct_size = offsetof(aq_node_desc, check);
  desc.type_name = "old_scene";
  desc.category = "Scene";
  desc.outputs = out;
  desc.output_count = 1;
  std::string why;
  EXPECT_EQ(aq::node_type_from_desc(desc, "old.so", &why).name, "old_scene") << why;
}

}  // namespace
