// The editor's document on a port that takes several links (AQ_PORT_MULTI, scene_join's
// `objects`): linking adds a link (once per source) instead of replacing, undo removes it, a
// plain port still has its one link replaced, and the links are written as an array.
#include "editor/document.h"

#include <aquarelle/core/graph_io.h>
#include <aquarelle/core/registry.h>
#include <gtest/gtest.h>

namespace aq::editor {
namespace {

PortInfo port(const std::string& name, aq_port_type type, bool optional = false,
              bool multi = false) {
  PortInfo info;
  info.name = name;
  info.type = type;
  info.optional = optional;
  info.multi = multi;
  return info;
}

const Registry& test_registry() {
  static const Registry registry = [] {
    Registry r;
    std::string why;
    NodeType object;
    object.name = "object";
    object.outputs = {port("object", AQ_PORT_SCENE)};
    EXPECT_TRUE(r.add(object, &why)) << why;
    NodeType join;
    join.name = "scene_join";
    join.inputs = {port("objects", AQ_PORT_SCENE, true, true)};
    join.outputs = {port("scene", AQ_PORT_SCENE)};
    EXPECT_TRUE(r.add(join, &why)) << why;
    NodeType gbuffer;
    gbuffer.name = "gbuffer";
    gbuffer.inputs = {port("scene", AQ_PORT_SCENE)};
    gbuffer.outputs = {port("albedo", AQ_PORT_IMAGE)};
    EXPECT_TRUE(r.add(gbuffer, &why)) << why;
    return r;
  }();
  return registry;
}

TEST(MultiLinkDocument, LinkingAddsUndoRemovesPlainPortsReplace) {
  Document doc(test_registry());
  auto a = doc.add_node("object", {0, 0});
  auto b = doc.add_node("object", {0, 100});
  auto join = doc.add_node("scene_join", {200, 0});
  auto gbuf = doc.add_node("gbuffer", {400, 0});
  ASSERT_TRUE(a.ok() && b.ok() && join.ok() && gbuf.ok());
  ASSERT_TRUE(doc.link({*a, "object"}, *join, "objects").ok());
  ASSERT_TRUE(doc.link({*b, "object"}, *join, "objects").ok());
  ASSERT_TRUE(doc.link({*a, "object"}, *join, "objects").ok());  // already there: no twin
  EXPECT_EQ(doc.graph().nodes.at(*join).inputs.links("objects"),
            (std::vector<PortRef>{{*a, "object"}, {*b, "object"}}));
  EXPECT_TRUE(doc.undo());
  EXPECT_TRUE(doc.undo());
  EXPECT_EQ(doc.graph().nodes.at(*join).inputs.links("objects"),
            (std::vector<PortRef>{{*a, "object"}}));
  ASSERT_TRUE(doc.link({*b, "object"}, *join, "objects").ok());

  ASSERT_TRUE(doc.link({*join, "scene"}, *gbuf, "scene").ok());
  auto join2 = doc.add_node("scene_join", {200, 200});
  ASSERT_TRUE(join2.ok());
  ASSERT_TRUE(doc.link({*join2, "scene"}, *gbuf, "scene").ok());
  EXPECT_EQ(doc.graph().nodes.at(*gbuf).inputs.count("scene"), 1u) << "a plain port: replaced";

  const std::string text = write_graph_text(doc.graph());
  EXPECT_NE(text.find("\"objects\": [\"" + *a + ".object\", \"" + *b + ".object\"]"),
            std::string::npos)
      << text;
}

}  // namespace
}  // namespace aq::editor
