// Issue 39: no node of any shipped graph and no installed node type can abort the editor when
// its parameter panel is drawn. Before, selecting a `scene` or `object` node handed its `seed`
// range [0, 2147483647] to ImGui::SliderInt, whose assertion (|min|, |max| <= 2^30) aborted the
// editor (exit 134). The real window under Xvfb, in scripted mode: one node of every installed
// type is added and selected, then every graph in graphs/ is opened and each of its nodes is
// selected, each for a few frames so its panel is drawn (a tall window: ImGui skips the
// widgets scrolled out of view, so only drawn ones can trip an assertion).
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "support/harness.h"
#include "window_fixture.h"

namespace {

namespace fs = std::filesystem;
using aq::test::EditorWindowTest;
using aq::test::read_json;

void select_and_draw(nlohmann::json& script, const std::string& id) {
  script.push_back({{"do", "select"}, {"nodes", {id}}});
  script.push_back({{"do", "wait"}, {"frames", 2}});
}

std::vector<fs::path> shipped_graphs() {
  std::vector<fs::path> graphs;
  for (const auto& entry : fs::directory_iterator(aq::test::source_path("graphs"))) {
    const fs::path& path = entry.path();
    if (path.extension() == ".json" && path.string().find(".autosave") == std::string::npos) {
      graphs.push_back(path);
    }
  }
  std::sort(graphs.begin(), graphs.end());
  return graphs;
}

TEST_F(EditorWindowTest, EveryNodeTypeAndEveryShippedNodeDrawsItsPanel) {
  nlohmann::json script = nlohmann::json::array();
  size_t types = 0;
  for (const std::string& type : aq::test::registry().names()) {
    const std::string id = "t" + std::to_string(types++);
    script.push_back({{"do", "add_node"}, {"type", type}, {"id", id}, {"at", {0, 120.0 * types}}});
    select_and_draw(script, id);
  }
  ASSERT_GT(types, 20u) << "the build's plugins were not found";
  size_t nodes = 0;
  const std::vector<fs::path> graphs = shipped_graphs();
  ASSERT_GE(graphs.size(), 10u);
  for (const fs::path& graph : graphs) {
    // Opened in place, so its textures resolve; selecting is no edit: nothing is written there.
    script.push_back({{"do", "open"}, {"path", graph.string()}});
    script.push_back({{"do", "wait"}, {"frames", 2}});
    for (const auto& [id, node] : read_json(graph)["nodes"].items()) {
      select_and_draw(script, id);
      ++nodes;
    }
  }
  std::ofstream(dir_ / "script.json") << script.dump(1);
  std::string log;
  const int status = run_editor("untitled.json --script script.json --quit --size 1280x1180", &log);
  ASSERT_EQ(status, 0) << "the editor did not finish the script (134: an assertion aborted it)\n"
                       << log.substr(log.size() > 6000 ? log.size() - 6000 : 0);
  // Every selection ran (and the script went on past it).
  size_t selected = 0;
  for (size_t at = log.find("(select): "); at != std::string::npos;
       at = log.find("(select): ", at + 1)) {
    ++selected;
  }
  EXPECT_EQ(selected, types + nodes) << log.substr(log.size() > 6000 ? log.size() - 6000 : 0);
  for (const fs::path& graph : graphs) {
    EXPECT_FALSE(fs::exists(fs::path(graph).replace_extension(".autosave.json"))) << graph;
  }
}

}  // namespace
