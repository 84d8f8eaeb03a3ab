// Tests of `aquarelle bench`: runs the executable on a small graph and checks what it measured
// (per-node times, the copy-pass yardstick and ratio, sweeps with finite errors whose reference
// re-renders exactly), the CSV and plot files, and its refusals of bad input.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>

#include "cli_support.h"
#include "support/harness.h"

namespace {

using nlohmann::json;

// The graphs are the test's own (graphs/ changes as effects land): a scene rasterised, then
// one image node.
std::string small_graph(const std::string& node_type) {
  return R"({
  "aquarelle": 1,
  "settings": { "width": 64, "height": 64, "fps": 24, "frames": [1, 1], "precision": "half" },
  "nodes": {
    "scene": { "type": "scene", "params": { "preset": "underwater", "seed": 7 } },
    "gbuf": { "type": "gbuffer", "inputs": { "scene": "scene.scene" } },
    "effect": { "type": ")" +
         node_type + R"(", "inputs": { "image": "gbuf.albedo" } }
  },
  "output": "effect.image"
})";
}

std::string write_graph(const std::filesystem::path& dir, const std::string& node_type) {
  const auto path = dir / (node_type + ".json");
  std::ofstream(path) << small_graph(node_type);
  return path.string();
}

struct BenchRun {
  int exit_code = -1;
  json report;
  std::string errors;
};

// Runs `aquarelle bench GRAPH ARGS --json` keeping stdout (the JSON) apart from stderr.
BenchRun bench_json(const std::string& node_type, const std::string& arguments,
                    const std::string& scratch_name) {
  const auto dir = aq::test::scratch_dir(scratch_name);
  const std::string err_path = (dir / "stderr.txt").string();
  auto result = aq::test::run_command("{ " + std::string(AQ_APP_PATH) + " bench " +
                                      write_graph(dir, node_type) + " " + arguments + " --json 2>" +
                                      err_path + "; }");
  BenchRun run;
  run.exit_code = result.exit_code;
  std::ifstream err(err_path);
  std::stringstream text;
  text << err.rdbuf();
  run.errors = text.str();
  run.report = json::parse(result.output, nullptr, false);
  return run;
}

bool finite_number(const json& value) {
  return value.is_number() && std::isfinite(value.get<double>());
}

class BenchOnBlurGraph : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    run_ = new BenchRun(bench_json("blur", "--size 64x64 --frames 3 --warmup 1", "bench_blur"));
  }
  static void TearDownTestSuite() {
    delete run_;
    run_ = nullptr;
  }
  static const json& report() { return run_->report; }
  static BenchRun* run_;
};
BenchRun* BenchOnBlurGraph::run_ = nullptr;

TEST_F(BenchOnBlurGraph, ExitsCleanlyWithJson) {
  ASSERT_EQ(run_->exit_code, 0) << run_->errors;
  ASSERT_TRUE(report().is_object()) << "stdout is not JSON; stderr:\n" << run_->errors;
  EXPECT_EQ(report()["size"], json::array({64, 64}));
}

TEST_F(BenchOnBlurGraph, TimesEveryNodeOfTheGraph) {
  ASSERT_TRUE(report().is_object());
  const json& nodes = report()["nodes"];
  ASSERT_TRUE(nodes.is_array());
  std::set<std::string> ids;
  for (const auto& node : nodes) {
    ids.insert(node["id"].get<std::string>());
    EXPECT_GT(node["wall_ms"]["median"].get<double>(), 0.0) << node["id"];
    EXPECT_GE(node["gpu_ms"]["median"].get<double>(), 0.0) << node["id"];
    EXPECT_LE(node["wall_ms"]["min"].get<double>(), node["wall_ms"]["median"].get<double>());
    EXPECT_LE(node["wall_ms"]["median"].get<double>(), node["wall_ms"]["max"].get<double>());
    EXPECT_EQ(node["runs"].get<int>(), 3) << "every node runs on each of the 3 frames";
  }
  EXPECT_EQ(ids, (std::set<std::string>{"scene", "gbuf", "effect"}));
  for (const auto& node : nodes) {
    if (node["id"] == "effect") {
      EXPECT_GT(node["gpu_ms"]["median"].get<double>(), 0.0);
    }
  }
}

TEST_F(BenchOnBlurGraph, ReportsTheCopyPassAndTheFrameInCopyPasses) {
  ASSERT_TRUE(report().is_object());
  const double copy_ms = report()["copy_pass_ms"].get<double>();
  const double ratio = report()["copy_passes_per_frame"].get<double>();
  EXPECT_GT(copy_ms, 0.0);
  EXPECT_GT(ratio, 0.0);
  EXPECT_NEAR(ratio, report()["frame_ms"].get<double>() / copy_ms, 1e-9 * ratio);
  // The graph rasterises a scene and blurs it: more than one copy pass of work.
  EXPECT_GT(report()["copy_passes_per_frame_every_node_runs"].get<double>(), 1.0);
}

TEST_F(BenchOnBlurGraph, SweepErrorsAreFiniteAndTheReferenceReRendersExactly) {
  ASSERT_TRUE(report().is_object());
  const json& sweeps = report()["sweeps"];
  ASSERT_TRUE(sweeps.is_array());
  ASSERT_FALSE(sweeps.empty());
  int references = 0;
  for (const auto& sweep : sweeps) {
    ASSERT_FALSE(sweep["points"].empty()) << sweep["series"];
    for (const auto& point : sweep["points"]) {
      EXPECT_TRUE(finite_number(point["max_abs"])) << sweep["series"] << " " << point["setting"];
      EXPECT_TRUE(finite_number(point["mean_abs"])) << sweep["series"] << " " << point["setting"];
      EXPECT_GT(point["time_ms"]["median"].get<double>(), 0.0) << sweep["series"];
      if (point["is_reference"].get<bool>()) {
        ++references;
        EXPECT_EQ(point["max_abs"].get<double>(), 0.0) << sweep["series"];
      }
    }
  }
  EXPECT_GE(references, 1) << "the pipeline preset sweep re-renders its reference";
}

TEST_F(BenchOnBlurGraph, BlurSweepAgainstTheCpuReferenceRanksTheMethods) {
  ASSERT_TRUE(report().is_object());
  if (!report()["cpu_references"].get<bool>()) GTEST_SKIP() << "no CPU references in this build";
  const json* uniform = nullptr;
  for (const auto& sweep : report()["sweeps"]) {
    if (sweep["kind"] == "cpu_reference" && sweep["series"] == "blur sigma=4") uniform = &sweep;
  }
  ASSERT_NE(uniform, nullptr);
  std::map<std::string, double> error;  // "setting precision" -> max abs
  for (const auto& p : (*uniform)["points"]) {
    error[p["setting"].get<std::string>() + " " + p["precision"].get<std::string>()] =
        p["max_abs"].get<double>();
  }
  // The exact separable Gaussian in float matches the double reference closely; the seed's
  // strided kernel is a different filter and is far off.
  EXPECT_LT(error.at("gaussian exact_taps float"), 1e-4);
  EXPECT_LT(error.at("gaussian exact_taps half"), 4e-3);
  EXPECT_GT(error.at("strided float"), 10 * error.at("gaussian linear_taps float"));
}

TEST(Bench, WritesCsvAndPlot) {
  const auto dir = aq::test::scratch_dir("bench_files");
  const std::string csv = (dir / "b.csv").string(), png = (dir / "b.png").string();
  auto result =
      aq::test::aquarelle("bench " + write_graph(dir, "tint") +
                          " --size 32x32 --frames 2 --warmup 1 -q --csv " + csv + " --plot " + png);
  ASSERT_EQ(result.exit_code, 0) << result.output;
  std::ifstream in(csv);
  std::string header, line;
  ASSERT_TRUE(std::getline(in, header));
  EXPECT_EQ(header.rfind("section,series,node,type,setting,precision,time_ms_median", 0), 0u);
  int copy_rows = 0, node_rows = 0, sweep_rows = 0;
  while (std::getline(in, line)) {
    copy_rows += line.rfind("copy_pass,", 0) == 0;
    node_rows += line.rfind("node,", 0) == 0;
    sweep_rows += line.rfind("sweep,", 0) == 0;
  }
  EXPECT_EQ(copy_rows, 1);
  EXPECT_EQ(node_rows, 6);   // scene, gbuf, effect in each of the two modes
  EXPECT_GE(sweep_rows, 7);  // the preset sweep: 3 presets x 2 precisions + the reference
  std::ifstream image(png, std::ios::binary);
  char signature[8] = {};
  image.read(signature, 8);
  EXPECT_EQ(std::string(signature + 1, 3), "PNG");
}

// The scene's normal smoothing against the sphere a bumpy low-poly test mesh stands for: flat
// facets are far off (~16 degrees), one iteration removes the bumps, and the graph's own count
// is among the points.
TEST(Bench, SmoothingSweepMeasuresTheFacetsAway) {
  const auto dir = aq::test::scratch_dir("bench_smoothing");
  auto result = aq::test::run_command(
      std::string(AQ_APP_PATH) + " bench " + aq::test::source_path("graphs/pot_smoothing.json") +
      " --node scene --size 32x32 --frames 1 --warmup 0 -q --json 2>" +
      (dir / "stderr.txt").string());
  ASSERT_EQ(result.exit_code, 0);
  const json report = json::parse(result.output, nullptr, false);
  ASSERT_FALSE(report.is_discarded());
  const json* sweep = nullptr;
  for (const auto& s : report["sweeps"]) {
    if (s["series"] == "scene smoothing") sweep = &s;
  }
  ASSERT_NE(sweep, nullptr);
  EXPECT_EQ((*sweep)["kind"], "analytic_reference");
  std::map<std::string, double> error;
  for (const auto& point : (*sweep)["points"]) {
    ASSERT_TRUE(finite_number(point["mean_abs"])) << point["setting"];
    error[point["setting"].get<std::string>()] = point["mean_abs"].get<double>();
  }
  ASSERT_TRUE(error.count("smoothing=0") && error.count("smoothing=1") &&
              error.count("smoothing=7"));
  EXPECT_GT(error.at("smoothing=0"), 3.0 * error.at("smoothing=1"));
  EXPECT_LT(error.at("smoothing=7"), error.at("smoothing=0"));
}

// A graph whose output is the caustic texture itself (as graphs/caustics.json): the texture's
// size follows the swept `resolution`, so the sweep compares at the reference's size instead of
// failing; the CPU sweeps put both estimators against the converged reference at the graph's
// texture size, with the reference's own error in the note.
TEST(Bench, CausticsTextureAsTheOutputIsComparedAtACommonSize) {
  const auto dir = aq::test::scratch_dir("bench_caustics");
  const auto graph = dir / "caustics.json";
  std::ofstream(graph) << R"({
  "aquarelle": 1,
  "settings": { "width": 32, "height": 32, "fps": 24, "frames": [1, 1], "precision": "half" },
  "nodes": { "caustics": { "type": "caustics", "params": { "resolution": 32, "grid": 48 } } },
  "output": "caustics.image"
})";
  auto result = aq::test::run_command(std::string(AQ_APP_PATH) + " bench " + graph.string() +
                                      " --node caustics --frames 1 --warmup 0 -q --json 2>" +
                                      (dir / "stderr.txt").string());
  ASSERT_EQ(result.exit_code, 0) << std::ifstream(dir / "stderr.txt").rdbuf();
  const json report = json::parse(result.output, nullptr, false);
  ASSERT_FALSE(report.is_discarded());
  std::map<std::string, const json*> sweeps;
  for (const auto& s : report["sweeps"]) sweeps[s["series"].get<std::string>()] = &s;
  ASSERT_TRUE(sweeps.count("caustics resolution"));
  for (const auto& point : (*sweeps.at("caustics resolution"))["points"]) {
    EXPECT_TRUE(finite_number(point["mean_abs"])) << point["setting"];
  }
  if (!report["cpu_references"].get<bool>()) GTEST_SKIP() << "no CPU references in this build";
  ASSERT_TRUE(sweeps.count("caustics coverage") && sweeps.count("caustics point"));
  const json& coverage = *sweeps.at("caustics coverage");
  EXPECT_NE(coverage["note"].get<std::string>().find("Richardson"), std::string::npos);
  EXPECT_NE(coverage["reference"].get<std::string>().find("texture 32x32"), std::string::npos);
  // Coverage at its finest grid beats point sampling at any grid.
  double best_point = 1e300;
  for (const auto& point : (*sweeps.at("caustics point"))["points"]) {
    best_point = std::min(best_point, point["mean_abs"].get<double>());
  }
  EXPECT_LT(coverage["points"].back()["mean_abs"].get<double>(), 0.5 * best_point);
}

TEST(Bench, RefusesBadInputWithExitCode1) {
  EXPECT_EQ(aq::test::aquarelle("bench --frobnicate").exit_code, 1);
  EXPECT_EQ(aq::test::aquarelle("bench /nonexistent/graph.json").exit_code, 1);
  EXPECT_EQ(
      aq::test::aquarelle("bench " + aq::test::source_path("graphs/tint.json") + " --frames 0")
          .exit_code,
      1);
  auto unknown = aq::test::aquarelle("bench " + aq::test::source_path("graphs/tint.json") +
                                     " --node no_such_node");
  EXPECT_EQ(unknown.exit_code, 1);
  EXPECT_NE(unknown.output.find("no such node type"), std::string::npos) << unknown.output;
}

TEST(Bench, TimesTheQualityPresetAsked) {
  auto run = bench_json("tint", "--size 64x64 --frames 1 --warmup 0 --no-sweep --quality draft",
                        "bench_quality");
  ASSERT_EQ(run.exit_code, 0) << run.errors;
  ASSERT_TRUE(run.report.is_object()) << run.errors;
  EXPECT_EQ(run.report["quality"], "draft");
  auto bad =
      aq::test::aquarelle("bench " + aq::test::source_path("graphs/tint.json") + " --quality best");
  EXPECT_EQ(bad.exit_code, 1);
  EXPECT_NE(bad.output.find("draft, preview or final"), std::string::npos) << bad.output;
  auto bad_set = aq::test::aquarelle("bench " + aq::test::source_path("graphs/tint.json") +
                                     " --set nosuch.amount=1");
  EXPECT_EQ(bad_set.exit_code, 1);
}

// --baseline: both graphs' frames timed alternately in one run. The baseline is the graph
// itself with a far heavier node (a blur of sigma 40 at 256x256 does dozens of passes more than a
// tint), so the tint graph's frame must come out as a fraction of it whatever the load.
TEST(Bench, BaselineTimesBothGraphsInOneRunAndGivesTheirRatio) {
  const auto dir = aq::test::scratch_dir("bench_baseline");
  const std::string heavy = (dir / "heavy.json").string();
  {
    std::string text = small_graph("blur");
    const std::string marker = R"("inputs": { "image": "gbuf.albedo" })";
    text.replace(text.find(marker), marker.size(),
                 R"("params": { "sigma": 40.0 }, "inputs": { "image": "gbuf.albedo" })");
    std::ofstream(heavy) << text;
  }
  auto run =
      bench_json("tint", "--size 256x256 --frames 3 --warmup 1 --no-sweep --baseline " + heavy,
                 "bench_baseline_run");
  ASSERT_EQ(run.exit_code, 0) << run.errors;
  ASSERT_TRUE(run.report.is_object()) << run.errors;
  const json& baseline = run.report["baseline"];
  ASSERT_TRUE(baseline.is_object()) << run.report.dump(2);
  EXPECT_EQ(baseline["graph"], heavy);
  EXPECT_EQ(baseline["frame_ms"]["count"], 3);
  EXPECT_EQ(baseline["baseline_frame_ms"]["count"], 3);
  EXPECT_EQ(baseline["pair_ratio"]["count"], 3);
  ASSERT_TRUE(finite_number(baseline["ratio_of_medians"]));
  const double ratio = baseline["ratio_of_medians"].get<double>();
  EXPECT_GT(ratio, 0.0);
  EXPECT_LT(ratio, 0.8) << "a tint cannot cost what a sigma-40 blur does";
  EXPECT_NEAR(ratio,
              baseline["frame_ms"]["median"].get<double>() /
                  baseline["baseline_frame_ms"]["median"].get<double>(),
              1e-9);

  // Without --baseline the report says so; a baseline that cannot be read names the option.
  auto plain =
      bench_json("tint", "--size 64x64 --frames 1 --warmup 0 --no-sweep", "bench_baseline_none");
  ASSERT_EQ(plain.exit_code, 0) << plain.errors;
  EXPECT_TRUE(plain.report["baseline"].is_null());
  auto missing = aq::test::aquarelle("bench " + aq::test::source_path("graphs/tint.json") +
                                     " --no-sweep --baseline /nonexistent/base.json");
  EXPECT_EQ(missing.exit_code, 1);
  EXPECT_NE(missing.output.find("--baseline"), std::string::npos) << missing.output;
}

TEST(Bench, HelpDescribesTheCommand) {
  auto help = aq::test::aquarelle("bench --help");
  EXPECT_EQ(help.exit_code, 0);
  EXPECT_NE(help.output.find("copy pass"), std::string::npos);
  EXPECT_NE(help.output.find("--plot"), std::string::npos);
}

}  // namespace
