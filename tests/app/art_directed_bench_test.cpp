// `aquarelle bench` sweeps the seed 002 nodes that have no sweep of their own elsewhere:
// dilution's turbulence octaves against reference::dilution, control_map's octaves against 8
// octaves, and hand_tremor's amplitude against the graph without a tremor. Runs the executable
// on graphs/windmill.json at a tiny size, one frame per point. And the node table's error
// column: each node that runs an approximation against the same node at its exact setting.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <sstream>

#include "cli_support.h"
#include "support/harness.h"

namespace {

using nlohmann::json;

bool finite_number(const json& value) {
  return value.is_number() && std::isfinite(value.get<double>());
}

TEST(ArtDirectedBench, SweepsDilutionControlMapAndHandTremor) {
  const auto dir = aq::test::scratch_dir("art_directed_bench");
  const std::string err_path = (dir / "stderr.txt").string();
  auto result = aq::test::run_command(
      "{ " + std::string(AQ_APP_PATH) + " bench " + aq::test::source_path("graphs/windmill.json") +
      " --node dilution --node control_map --node hand_tremor --size 64x36 --frames 1"
      " --warmup 0 -q --json 2>" +
      err_path + "; }");
  std::stringstream errors;
  errors << std::ifstream(err_path).rdbuf();
  ASSERT_EQ(result.exit_code, 0) << errors.str();
  const json report = json::parse(result.output, nullptr, false);
  ASSERT_TRUE(report.is_object()) << errors.str();
  std::map<std::string, const json*> sweeps;
  for (const auto& s : report["sweeps"]) sweeps[s["series"].get<std::string>()] = &s;

  ASSERT_TRUE(sweeps.count("control_map octaves"));
  const json& octaves = *sweeps.at("control_map octaves");
  ASSERT_FALSE(octaves["points"].empty());
  for (const auto& point : octaves["points"]) {
    EXPECT_TRUE(finite_number(point["mean_abs"])) << point["setting"];
  }
  EXPECT_EQ(octaves["points"].back()["mean_abs"].get<double>(), 0.0);  // the reference again

  ASSERT_TRUE(sweeps.count("hand_tremor amplitude"));
  const json& tremor = *sweeps.at("hand_tremor amplitude");
  EXPECT_EQ(tremor["kind"], "identity_reference");
  ASSERT_EQ(tremor["points"].size(), 4u);
  // Twice the graph's amplitude moves the picture more than a quarter of it.
  EXPECT_GT(tremor["points"][3]["mean_abs"].get<double>(),
            tremor["points"][0]["mean_abs"].get<double>());

  if (!report["cpu_references"].get<bool>()) GTEST_SKIP() << "no CPU references in this build";
  ASSERT_TRUE(sweeps.count("dilution turbulence"));
  const json& dilution = *sweeps.at("dilution turbulence");
  EXPECT_EQ(dilution["kind"], "cpu_reference");
  ASSERT_EQ(dilution["points"].size(), 8u);  // octaves 1, 2, 4, 8 in half and float
  for (const auto& point : dilution["points"]) {
    const double bound = point["precision"] == "float" ? 1e-5 : 3e-3;
    EXPECT_LE(point["max_abs"].get<double>(), bound) << point["setting"] << point["precision"];
  }
}

// The JSON report of `aquarelle bench GRAPH --no-sweep` at 64x36 with `extra` arguments.
json bench_report(const std::string& graph, const std::string& extra, const std::string& name) {
  const auto dir = aq::test::scratch_dir(name);
  const std::string err_path = (dir / "stderr.txt").string();
  auto result = aq::test::run_command("{ " + std::string(AQ_APP_PATH) + " bench " +
                                      aq::test::source_path(graph) +
                                      " --no-sweep --size 64x36 --frames 1 --warmup 0 -q --json " +
                                      extra + " 2>" + err_path + "; }");
  std::stringstream errors;
  errors << std::ifstream(err_path).rdbuf();
  EXPECT_EQ(result.exit_code, 0) << errors.str();
  json report = json::parse(result.output, nullptr, false);
  EXPECT_TRUE(report.is_object()) << errors.str();
  return report;
}

std::map<std::string, json> node_rows(const json& report) {
  std::map<std::string, json> rows;
  for (const auto& node : report["modes"]["cached_static_nodes"]["nodes"])
    rows[node["id"].get<std::string>()] = node;
  return rows;
}

TEST(ArtDirectedBench, TheNodeTableGivesEachApproximationItsErrorAgainstTheExactNode) {
  const json report = bench_report("graphs/art_directed.json", "", "node_error_default");
  ASSERT_TRUE(report.is_object());
  auto rows = node_rows(report);
  // Bleed on cells, edge blur on 2x2 cells, clouds one ray per block: each against itself at
  // resolution 1 (the clouds also at 256 steps).
  for (const char* id : {"bleeding", "edges", "spray"}) {
    ASSERT_TRUE(rows.count(id)) << id;
    const json& error = rows[id]["error"];
    ASSERT_TRUE(error.is_object()) << id << ": " << rows[id].dump();
    EXPECT_FALSE(error["exact"].get<bool>()) << id;
    EXPECT_NE(error["against"].get<std::string>().find("resolution=1"), std::string::npos);
    ASSERT_TRUE(finite_number(error["mean_abs"])) << id;
    EXPECT_GT(error["mean_abs"].get<double>(), 0.0) << id << ": a shortcut shows an error";
    EXPECT_LT(error["mean_abs"].get<double>(), 0.05) << id;
  }
  // A node with no shortcut has no error entry.
  ASSERT_TRUE(rows.count("paint"));
  EXPECT_TRUE(rows["paint"]["error"].is_null());

  // At its exact setting the node is marked exact, not measured against itself.
  const json exact =
      bench_report("graphs/art_directed.json", "--set bleeding.resolution=1", "node_error_exact");
  auto exact_rows = node_rows(exact);
  ASSERT_TRUE(exact_rows.count("bleeding"));
  ASSERT_TRUE(exact_rows["bleeding"]["error"].is_object());
  EXPECT_TRUE(exact_rows["bleeding"]["error"]["exact"].get<bool>());
}

// The text table gives a node fused into its reader's pass its error too: the spray's row used
// to say only "fused into its reader's pass", so the clouds' error was in the JSON alone.
TEST(ArtDirectedBench, AFusedNodesRowInTheTableStatesItsError) {
  const auto dir = aq::test::scratch_dir("node_error_fused_text");
  auto result = aq::test::run_command("{ " + std::string(AQ_APP_PATH) + " bench " +
                                      aq::test::source_path("graphs/waterfall.json") +
                                      " --no-sweep --size 64x36 --frames 1 --warmup 0 -q 2>" +
                                      (dir / "stderr.txt").string() + "; }");
  ASSERT_EQ(result.exit_code, 0) << result.output;
  std::istringstream lines(result.output);
  std::string line, spray;
  while (std::getline(lines, line))
    if (line.rfind("spray ", 0) == 0) spray = line;
  const std::string fused = "fused into its reader's pass";
  const size_t at = spray.find(fused);
  ASSERT_NE(at, std::string::npos) << "the spray is fused into the relief's pass:\n"
                                   << result.output;
  std::istringstream cells(spray.substr(at + fused.size()));
  double mean_abs = -1.0, max_abs = -1.0;
  cells >> mean_abs >> max_abs;
  ASSERT_FALSE(cells.fail()) << "no error after the fused row: " << spray;
  EXPECT_GT(mean_abs, 0.0) << spray;
  EXPECT_GE(max_abs, mean_abs) << spray;
}

// A node whose exact setting changes its output's size (the shadow map at 4096) is compared
// after resampling, and the bench still reports: it used to stop with "output is 1024x1024 but
// the reference is 4096x4096".
TEST(ArtDirectedBench, AnExactSettingOfAnotherSizeIsResampledNotFatal) {
  const json report = bench_report("graphs/underwater.json", "", "node_error_sizes");
  ASSERT_TRUE(report.is_object());
  auto rows = node_rows(report);
  ASSERT_TRUE(rows.count("shadow"));
  const json& error = rows["shadow"]["error"];
  ASSERT_TRUE(error.is_object());
  EXPECT_TRUE(finite_number(error["mean_abs"])) << error.dump();
  EXPECT_NE(error["note"].get<std::string>().find("resampled"), std::string::npos);
}

}  // namespace
