// Bypass without GL (core/bypass.h, graph_read.cpp, graph_write.cpp): "bypass" read from and
// written on the node, a wrong value refused by place, editor.bypassed of older editors
// migrated onto the node, the rewrite before planning (chains, the requested output, scene
// ports), and a bypassed node with nothing to pass through refused by name.
#include <gtest/gtest.h>

#include <aquarelle/core/bypass.h>
#include <aquarelle/core/graph_io.h>

namespace {

aq::PortInfo port(const char* name, aq_port_type type, bool optional = false) {
  return aq::PortInfo{name, type, optional, ""};
}

aq::Registry fake_registry() {
  aq::Registry registry;
  std::string why;
  aq::NodeType source;
  source.name = "source";
  source.outputs = {port("image", AQ_PORT_IMAGE)};
  EXPECT_TRUE(registry.add(source, &why)) << why;
  aq::NodeType filter;
  filter.name = "filter";
  // A scene input first: bypass passes the first input *of the output's type*.
  filter.inputs = {port("scene", AQ_PORT_SCENE, true), port("image", AQ_PORT_IMAGE, true),
                   port("mask", AQ_PORT_IMAGE, true)};
  filter.outputs = {port("image", AQ_PORT_IMAGE)};
  EXPECT_TRUE(registry.add(filter, &why)) << why;
  return registry;
}

const aq::Registry& registry() {
  static const aq::Registry r = fake_registry();
  return r;
}

const char* kChain = R"({
  "aquarelle": 1,
  "nodes": {
    "src": { "type": "source" },
    "a": { "type": "filter", "bypass": true, "inputs": { "image": "src.image" } },
    "b": { "type": "filter", "bypass": true, "inputs": { "image": "a.image", "mask": "src.image" } },
    "c": { "type": "filter", "inputs": { "image": "b.image" } }
  },
  "output": "c.image"
}
)";

TEST(Bypass, IsReadFromTheNodeAndWrittenBackUnchanged) {
  auto read = aq::read_graph_text(kChain, registry(), "chain.json");
  ASSERT_TRUE(read.problems.empty()) << read.problems.front().message;
  EXPECT_TRUE(read.graph.nodes.at("a").bypass);
  EXPECT_TRUE(read.graph.nodes.at("b").bypass);
  EXPECT_FALSE(read.graph.nodes.at("c").bypass);
  EXPECT_EQ(aq::write_graph_text(read.graph, kChain), kChain) << "unedited: the same bytes";
  // Enabling a node rewrites only its value; bypassing another adds one member to it.
  aq::Graph edited = read.graph;
  edited.nodes.at("a").bypass = false;
  edited.nodes.at("c").bypass = true;
  const std::string patched = aq::write_graph_text(edited, kChain);
  EXPECT_NE(patched.find(R"("a": { "type": "filter", "bypass": false,)"), std::string::npos)
      << patched;
  EXPECT_NE(patched.find(R"("bypass": true)"), std::string::npos) << patched;
  auto again = aq::read_graph_text(patched, registry(), "chain.json");
  ASSERT_TRUE(again.problems.empty());
  EXPECT_TRUE(again.graph.nodes.at("c").bypass);
  // The canonical writer puts it after the type, only when true.
  const std::string canonical = aq::write_graph_text(read.graph);
  EXPECT_NE(canonical.find("\"type\": \"filter\",\n      \"bypass\": true,"), std::string::npos)
      << canonical;
  EXPECT_EQ(canonical.find("\"bypass\": false"), std::string::npos);
}

TEST(Bypass, AValueOtherThanTrueOrFalseIsRefusedAtItsPlace) {
  auto read = aq::read_graph_text(R"({"aquarelle": 1, "nodes": {
    "src": {"type": "source", "bypass": "yes"}}, "output": "src.image"})",
                                  registry(), "bad.json");
  ASSERT_EQ(read.problems.size(), 1u);
  EXPECT_EQ(read.problems[0].node, "src");
  EXPECT_NE(read.problems[0].message.find("\"bypass\" must be true or false"), std::string::npos);
}

TEST(Bypass, EditorSectionMarksOfOlderEditorsMoveOntoTheNode) {
  auto read = aq::read_graph_text(R"({"aquarelle": 1, "nodes": {
    "src": {"type": "source"},
    "a": {"type": "filter", "inputs": {"image": "src.image"}}},
    "output": "a.image",
    "editor": {"bypassed": {"a": true}, "positions": {"a": [1, 2]}}})",
                                  registry(), "old.json");
  ASSERT_TRUE(read.problems.empty());
  EXPECT_TRUE(read.graph.nodes.at("a").bypass);
  EXPECT_FALSE(read.graph.editor.contains("bypassed"));
  EXPECT_TRUE(read.graph.editor.contains("positions"));
}

TEST(Bypass, ReadersOfABypassedNodeReadItsInputFollowingChains) {
  auto read = aq::read_graph_text(kChain, registry(), "chain.json");
  auto rewritten = aq::apply_bypass(read.graph, registry());
  ASSERT_TRUE(rewritten.ok()) << rewritten.message();
  EXPECT_EQ(rewritten->nodes.at("c").inputs.at("image"), (aq::PortRef{"src", "image"}));
  // The requested output of a bypassed node (the editor viewing it) is its input's.
  auto viewed = aq::bypassed_graph(read.graph, registry(), aq::PortRef{"b", "image"});
  ASSERT_TRUE(viewed.ok());
  EXPECT_EQ(viewed->output, (aq::PortRef{"src", "image"}));
  ASSERT_TRUE(viewed->rewritten.has_value());
  // A graph without bypassed nodes is unchanged.
  aq::Graph plain = read.graph;
  for (auto& [id, node] : plain.nodes) node.bypass = false;
  EXPECT_EQ(aq::apply_bypass(plain, registry())->nodes.at("c").inputs.at("image"),
            (aq::PortRef{"b", "image"}));
  // ... and the evaluator reads it as it is, without a copy.
  auto unchanged = aq::bypassed_graph(plain, registry(), aq::PortRef{"b", "image"});
  ASSERT_TRUE(unchanged.ok());
  EXPECT_FALSE(unchanged->rewritten.has_value());
  EXPECT_EQ(&unchanged->graph(plain), &plain);
  EXPECT_EQ(unchanged->output, (aq::PortRef{"b", "image"}));
}

TEST(Bypass, NothingToPassThroughIsAnErrorNamingTheNode) {
  const char* text = R"({"aquarelle": 1, "nodes": {
    "src": {"type": "source", "bypass": true},
    "a": {"type": "filter", "inputs": {"image": "src.image"}}},
    "output": "a.image"})";
  auto read = aq::read_graph_text(text, registry(), "source.json");
  ASSERT_EQ(read.problems.size(), 1u) << "validation reports it";
  EXPECT_EQ(read.problems[0].node, "src");
  auto rewritten = aq::apply_bypass(read.graph, registry());
  ASSERT_FALSE(rewritten.ok());
  EXPECT_NE(rewritten.message().find("node 'src' (source) is bypassed but has no image "
                                     "input"),
            std::string::npos)
      << rewritten.message();
  // An unlinked input: nothing to pass either.
  auto unlinked = aq::read_graph_text(R"({"aquarelle": 1, "nodes": {
    "a": {"type": "filter", "bypass": true}}, "output": "a.image"})",
                                      registry(), "unlinked.json");
  auto refused = aq::apply_bypass(unlinked.graph, registry());
  ASSERT_FALSE(refused.ok());
  EXPECT_NE(refused.message().find("input 'image' is not linked"), std::string::npos)
      << refused.message();
  // A bypassed node nobody reads is no problem.
  auto unread = aq::read_graph_text(R"({"aquarelle": 1, "nodes": {
    "src": {"type": "source"}, "lone": {"type": "source", "bypass": true}},
    "output": "src.image"})",
                                    registry(), "unread.json");
  EXPECT_TRUE(unread.problems.empty());
  EXPECT_TRUE(aq::apply_bypass(unread.graph, registry()).ok());
}

}  // namespace
