// The evaluator's first step on its own (nodes/src/node_call.h): a node's cache key and its
// inputs, computed from the graph, the plan and the states of the nodes it reads, with no GL.
// The key decides whether a node runs again, so what it follows is asserted here directly.
#include <gtest/gtest.h>

#include <aquarelle/core/graph_io.h>
#include <aquarelle/core/plan.h>

#include "../../nodes/src/node_call.h"
#include "support/harness.h"

namespace aq::test {
namespace {

// noise -> tint; the tests prepare tint's call against a hand-made state of noise.
const char* kPair = R"({
  "aquarelle": 1,
  "settings": {"width": 32, "height": 16},
  "nodes": {
    "noise": {"type": "noise", "params": {"scale": 4}},
    "tint": {"type": "tint", "params": {"amount": 0.3}, "inputs": {"image": "noise.image"}}
  },
  "output": "tint.image"
})";

struct Prepared {
  Graph graph;
  Plan plan;
  EvalOptions options;
  std::map<std::string, NodeState> states;

  explicit Prepared(const char* text) {
    auto read = read_graph_text(text, registry(), "node call test");
    EXPECT_TRUE(read.ok());
    graph = read.graph;
    auto compiled = compile_plan(graph, registry(), PlanOptions{});
    EXPECT_TRUE(compiled.ok()) << compiled.message();
    plan = *compiled;
    NodeState& noise = states["noise"];
    noise.type = registry().find("noise");
    noise.images.resize(1);
    noise.scenes.resize(1);
    noise.key = 7;
  }
  Result<NodeCall> call(const std::string& id) {
    const FrameConstants frame = frame_constants(graph, plan, options, nullptr, 1);
    return prepare_node_call(*plan.find(id), graph.nodes.at(id), frame, states);
  }
};

TEST(NodeCall, TheKeyFollowsTheInputsKeyTheSelfKeyDoesNot) {
  Prepared prepared(kPair);
  auto before = prepared.call("tint");
  ASSERT_TRUE(before.ok()) << before.message();
  prepared.states["noise"].key = 8;  // what noise computed changed
  auto after = prepared.call("tint");
  ASSERT_TRUE(after.ok()) << after.message();
  EXPECT_NE(before->key, after->key);
  EXPECT_EQ(before->self_key, after->self_key) << "the node's own key leaves its inputs out";
  EXPECT_EQ(before->inputs.values[0].connected, 1u);
  EXPECT_NE(after->inputs.keys[0], before->inputs.keys[0]);
}

TEST(NodeCall, BothKeysFollowTheParametersAndTheSize) {
  Prepared prepared(kPair);
  const NodeCall first = *prepared.call("tint");
  EXPECT_EQ(prepared.call("tint")->key, first.key) << "the same call twice has the same key";
  prepared.graph.nodes.at("tint").params["amount"] = 0.4;
  const NodeCall amount = *prepared.call("tint");
  EXPECT_NE(amount.key, first.key);
  EXPECT_NE(amount.self_key, first.self_key);
  EXPECT_DOUBLE_EQ(amount.params.params[0].f[0], 0.4);
  prepared.graph.settings.width = 64;
  const NodeCall wider = *prepared.call("tint");
  EXPECT_NE(wider.key, amount.key);
  EXPECT_NE(wider.self_key, amount.self_key);
}

TEST(NodeCall, AnUnconnectedRequiredInputNamesTheNodeAndThePort) {
  Prepared prepared(kPair);
  prepared.graph.nodes.at("tint").inputs.clear();
  auto call = prepared.call("tint");
  ASSERT_FALSE(call.ok());
  EXPECT_NE(call.message().find("node 'tint' (tint): required input 'image' is not connected"),
            std::string::npos)
      << call.message();
}

TEST(NodeCall, AStringWithANulIsRefusedNamingTheParameter) {
  Prepared prepared(R"({"aquarelle": 1, "settings": {"width": 8, "height": 8},
    "nodes": {"in": {"type": "image_input", "params": {"name": "a"}}}, "output": "in.image"})");
  prepared.graph.nodes.at("in").params["name"] = std::string("a\0b", 3);
  auto call = prepared.call("in");
  ASSERT_FALSE(call.ok());
  EXPECT_NE(call.message().find("node 'in' (image_input), parameter 'name': the value contains "
                                "a NUL character"),
            std::string::npos)
      << call.message();
}

TEST(NodeCall, ARelativePathResolvesAgainstTheGraphsFolder) {
  const NodeType& read = *registry().find("read");
  Node node;
  node.type = "read";
  node.params["path"] = "textures/../paper.png";
  uint64_t key = 0;
  const ParamValues values = convert_params(node, read, "/graphs/demo", &key);
  EXPECT_STREQ(values.params[0].s, "/graphs/demo/paper.png");
  node.params["path"] = "/abs/paper.png";
  EXPECT_STREQ(convert_params(node, read, "/graphs/demo", &key).params[0].s, "/abs/paper.png");
}

}  // namespace
}  // namespace aq::test
