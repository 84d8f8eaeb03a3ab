// `aquarelle bench` sweeps the seed 002 nodes that have no sweep of their own elsewhere:
// dilution's turbulence octaves against reference::dilution, control_map's octaves against 8
// octaves, and hand_tremor's amplitude against the graph without a tremor. Runs the executable
// on graphs/windmill.json at a tiny size, one frame per point.
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

}  // namespace
