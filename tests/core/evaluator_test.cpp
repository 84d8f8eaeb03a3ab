// The evaluator: pulls only what the output needs, re-runs only what changed, returns textures
// to the pool after their last reader, reports plugin failures naming the node.
#include <gtest/gtest.h>

#include <aquarelle/core/evaluator.h>
#include <aquarelle/core/gl_context.h>
#include <aquarelle/core/plugin_loader.h>

#include "support/harness.h"

namespace aq {
namespace {

class EvaluatorTest : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    registry_ = new Registry();
    plugins_ = new PluginSet();
    register_builtin_nodes(*registry_);
    std::string why;
    ASSERT_TRUE(plugins_->load_file(std::string(AQ_TEST_PLUGIN_DIR) + "/aquarelle_test_nodes.so",
                                    *registry_, &why))
        << why;
    auto context = create_headless_context(GlBackend::kAuto);
    ASSERT_TRUE(context.ok()) << context.message();
    context_ = context->release();
  }

  static Node add_node(double offset, const std::string& source = "") {
    Node node;
    node.type = "test_add";
    node.params["offset"] = offset;
    if (!source.empty()) node.inputs["image"] = PortRef{source, "image"};
    return node;
  }

  static Graph small_graph() {
    // a -> b -> c (output), and d hanging off a, which the output does not need.
    Graph graph;
    graph.settings.width = 8;
    graph.settings.height = 8;
    graph.settings.precision = "float";
    graph.nodes["a"] = add_node(0.25);
    graph.nodes["b"] = add_node(0.5, "a");
    graph.nodes["c"] = add_node(0.125, "b");
    graph.nodes["d"] = add_node(1.0, "a");
    graph.output = PortRef{"c", "image"};
    return graph;
  }

  static Registry* registry_;
  static PluginSet* plugins_;
  static GlContext* context_;
};

Registry* EvaluatorTest::registry_ = nullptr;
PluginSet* EvaluatorTest::plugins_ = nullptr;
GlContext* EvaluatorTest::context_ = nullptr;

TEST_F(EvaluatorTest, RunsOnlyTheNodesTheOutputNeeds) {
  Evaluator evaluator(*context_, *registry_);
  Graph graph = small_graph();
  auto result = evaluator.evaluate(graph, EvalOptions{});
  ASSERT_TRUE(result.ok()) << result.message();
  EXPECT_EQ(evaluator.run_counts().count("d"), 0u) << "d is culled: nothing reads it";
  EXPECT_EQ(evaluator.run_counts().at("a"), 1);
  auto pixels = evaluator.read_back(*result);
  ASSERT_TRUE(pixels.ok());
  EXPECT_FLOAT_EQ(pixels->at(3, 3, 0), 0.875f);
  EXPECT_FLOAT_EQ(pixels->at(3, 3, 3), 1.0f);
}

TEST_F(EvaluatorTest, ParameterChangeRerunsOnlyDownstream) {
  Evaluator evaluator(*context_, *registry_);
  Graph graph = small_graph();
  ASSERT_TRUE(evaluator.evaluate(graph, EvalOptions{}).ok());
  ASSERT_TRUE(evaluator.evaluate(graph, EvalOptions{}).ok());
  EXPECT_EQ(evaluator.run_counts().at("a"), 1) << "unchanged: not run again";
  EXPECT_EQ(evaluator.run_counts().at("c"), 1);

  graph.nodes["b"].params["offset"] = 0.0;
  auto result = evaluator.evaluate(graph, EvalOptions{});
  ASSERT_TRUE(result.ok());
  EXPECT_EQ(evaluator.run_counts().at("a"), 1) << "upstream of the edit: reused";
  EXPECT_EQ(evaluator.run_counts().at("b"), 2);
  EXPECT_EQ(evaluator.run_counts().at("c"), 2);
  auto pixels = evaluator.read_back(*result);
  ASSERT_TRUE(pixels.ok());
  EXPECT_FLOAT_EQ(pixels->at(0, 0, 1), 0.375f);
}

TEST_F(EvaluatorTest, TimeDependentNodesRerunEachFrameOthersDoNot) {
  Evaluator evaluator(*context_, *registry_);
  Graph graph = small_graph();
  graph.nodes["t"] = add_node(0.0, "a");
  graph.nodes["t"].type = "test_time";
  graph.output = PortRef{"t", "image"};
  for (int frame = 1; frame <= 3; ++frame) {
    EvalOptions options;
    options.frame = frame;
    ASSERT_TRUE(evaluator.evaluate(graph, options).ok());
  }
  EXPECT_EQ(evaluator.run_counts().at("t"), 3);
  EXPECT_EQ(evaluator.run_counts().at("a"), 1);
}

TEST_F(EvaluatorTest, PoolPeakStaysBoundedOnALongChain) {
  Evaluator evaluator(*context_, *registry_);
  Graph graph;
  graph.settings.width = 16;
  graph.settings.height = 16;
  graph.settings.precision = "float";  // 49 additions in half precision drift by ~7e-3
  graph.nodes["n0"] = add_node(0.0);
  for (int i = 1; i < 50; ++i) {
    graph.nodes["n" + std::to_string(i)] = add_node(0.01, "n" + std::to_string(i - 1));
  }
  graph.output = PortRef{"n49", "image"};
  EvalOptions options;
  options.retain_outputs = false;
  options.retain_static_outputs = false;
  auto result = evaluator.evaluate(graph, options);
  ASSERT_TRUE(result.ok()) << result.message();
  EXPECT_EQ(evaluator.run_counts().size(), 50u);
  EXPECT_LE(evaluator.pool().peak_live_count(), 3u)
      << "a chain needs its current input and output only";
  EXPECT_LE(evaluator.pool().created_count(), 3u);
  auto pixels = evaluator.read_back(*result);
  ASSERT_TRUE(pixels.ok());
  EXPECT_NEAR(pixels->at(0, 0, 0), 0.49f, 2e-3f);
  result = Result<TextureRef>(make_error("released"));
  EXPECT_EQ(evaluator.pool().live_count(), 0u) << "every texture back in the pool";

  // Another frame reuses the pool's textures: none created.
  size_t created = evaluator.pool().created_count();
  ASSERT_TRUE(evaluator.evaluate(graph, options).ok());
  EXPECT_EQ(evaluator.pool().created_count(), created);
}

TEST_F(EvaluatorTest, BatchModeKeepsStaticResultsAndReleasesTheRest) {
  Evaluator evaluator(*context_, *registry_);
  Graph graph = small_graph();  // a -> b -> c, all static
  graph.nodes["t"] = add_node(0.0, "c");
  graph.nodes["t"].type = "test_time";
  graph.nodes["u"] = add_node(0.5, "t");
  graph.output = PortRef{"u", "image"};
  EvalOptions options;
  options.retain_outputs = false;
  for (int frame = 1; frame <= 3; ++frame) {
    options.frame = frame;
    auto result = evaluator.evaluate(graph, options);
    ASSERT_TRUE(result.ok()) << result.message();
  }
  EXPECT_EQ(evaluator.run_counts().at("a"), 1) << "static: computed once, kept";
  EXPECT_EQ(evaluator.run_counts().at("c"), 1);
  EXPECT_EQ(evaluator.run_counts().at("t"), 3);
  EXPECT_EQ(evaluator.run_counts().at("u"), 3);
  EXPECT_EQ(evaluator.pool().live_count(), 3u) << "only a, b and c stay out of the pool";
}

TEST_F(EvaluatorTest, PluginFailureNamesTheNode) {
  Evaluator evaluator(*context_, *registry_);
  Graph graph = small_graph();
  graph.nodes["boom"] = add_node(0, "b");
  graph.nodes["boom"].type = "test_fail";
  graph.nodes["boom"].params.clear();
  graph.output = PortRef{"boom", "image"};
  auto result = evaluator.evaluate(graph, EvalOptions{});
  ASSERT_FALSE(result.ok());
  EXPECT_NE(result.message().find("node 'boom' (test_fail)"), std::string::npos)
      << result.message();
  EXPECT_NE(result.message().find("always fails"), std::string::npos);
}

TEST_F(EvaluatorTest, ShaderErrorNamesNodeFileAndLine) {
  Evaluator evaluator(*context_, *registry_);
  Graph graph;
  graph.settings.width = 4;
  graph.settings.height = 4;
  Node bad;
  bad.type = "test_bad_shader";
  graph.nodes["shady"] = bad;
  graph.output = PortRef{"shady", "image"};
  auto result = evaluator.evaluate(graph, EvalOptions{});
  ASSERT_FALSE(result.ok());
  EXPECT_NE(result.message().find("node 'shady'"), std::string::npos) << result.message();
  EXPECT_NE(result.message().find("broken.frag:4"), std::string::npos) << result.message();
}

TEST_F(EvaluatorTest, UnknownOutputAndMissingNodeAreErrors) {
  Evaluator evaluator(*context_, *registry_);
  Graph graph = small_graph();
  auto result = evaluator.evaluate(graph, EvalOptions{}, PortRef{"nope", "image"});
  ASSERT_FALSE(result.ok());
  EXPECT_NE(result.message().find("'nope'"), std::string::npos);
  result = evaluator.evaluate(graph, EvalOptions{}, PortRef{"c", "nothere"});
  ASSERT_FALSE(result.ok());
  EXPECT_NE(result.message().find("nothere"), std::string::npos);
}

}  // namespace
}  // namespace aq
