// graphs/deep_ocean.json (issue 38, seed 001's scene) and its watercolor sibling validate and
// render animated frames (small, to keep CI short; the 1280x720 picture is in docs/), with the
// parts the issue asks to see: terrain, ship and sails, jellyfish, the image environment behind
// them and caustics that move; `aquarelle bench` sweeps every node and parameter the issue
// added (blend_count, shift, blend_interval, environment, terrain_cells, swim_forward,
// light_shafts), each against its reference.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <map>
#include <set>
#include <sstream>
#include <string>

#include "cli_support.h"
#include "support/harness.h"

namespace {

using aq::ImageF;

ImageF render(const std::string& graph, const std::string& output, int frame) {
  aq::test::RenderOptions options;
  options.width = 192;
  options.height = 108;
  options.output = output;
  options.frame = frame;
  options.precision = "half";
  options.quality = "preview";
  auto image = aq::test::render_graph_file(aq::test::source_path(graph), options);
  EXPECT_TRUE(image.ok()) << (image.ok() ? "" : image.message());
  return image.ok() ? *image : ImageF();
}

TEST(DeepOcean, BothGraphsValidate) {
  for (const char* graph : {"graphs/deep_ocean.json", "graphs/deep_ocean_watercolor.json"}) {
    const auto result = aq::test::aquarelle("validate " + aq::test::source_path(graph));
    EXPECT_EQ(result.exit_code, 0) << result.output;
    EXPECT_EQ(result.output.find("warning"), std::string::npos) << result.output;
  }
}

TEST(DeepOcean, EveryPartIsInViewAndTheFrameMoves) {
  const ImageF id = render("graphs/deep_ocean.json", "gbuf.id", 1);
  std::set<int> seen;
  for (int i = 0; i < id.width * id.height; ++i)
    seen.insert(static_cast<int>(id.pixels[i * id.channels]));
  for (int wanted : {0, 1, 2, 12, 20, 21}) {  // background, terrain, a rock, ship, jellyfish
    EXPECT_TRUE(seen.count(wanted)) << "id " << wanted << " is not in view";
  }
  const ImageF first = render("graphs/deep_ocean.json", "", 1);
  const ImageF later = render("graphs/deep_ocean.json", "", 13);
  ASSERT_EQ(first.pixels.size(), later.pixels.size());
  double changed = 0.0, background_blue = 0.0, background_red = 0.0;
  int background = 0;
  for (size_t i = 0; i < first.pixels.size(); ++i)
    changed += std::abs(first.pixels[i] - later.pixels[i]);
  for (int i = 0; i < id.width * id.height; ++i) {
    if (id.pixels[i * id.channels] != 0.0f) continue;
    ++background;
    background_red += first.pixels[i * 4];
    background_blue += first.pixels[i * 4 + 2];
  }
  EXPECT_GT(changed / first.pixels.size(), 1e-3) << "animated: caustics, jellyfish, fish";
  ASSERT_GT(background, 0);
  EXPECT_GT(background_blue, 2.0 * background_red) << "the panorama's blue water behind";
  EXPECT_TRUE(aq::test::all_finite(first));
  const ImageF watercolor = render("graphs/deep_ocean_watercolor.json", "", 1);
  EXPECT_TRUE(aq::test::all_finite(watercolor));
}

// The god rays are in the picture: light_shafts adds light over the terrain's cliff and the
// open water, never takes any away, and it varies (streaks, not a uniform haze).
TEST(DeepOcean, LightShaftsAddStreaksOfLight) {
  const ImageF before = render("graphs/deep_ocean.json", "environment.image", 1);
  const ImageF after = render("graphs/deep_ocean.json", "shafts.image", 1);
  const ImageF id = render("graphs/deep_ocean.json", "gbuf.id", 1);
  ASSERT_EQ(before.pixels.size(), after.pixels.size());
  ASSERT_EQ(id.width, before.width);
  double least = 1e9, most = -1e9, on_terrain = 0.0;
  int terrain = 0;
  for (int i = 0; i < before.width * before.height; ++i) {
    const double added = after.pixels[4 * i + 2] - before.pixels[4 * i + 2];  // blue
    least = std::min(least, added), most = std::max(most, added);
    if (id.pixels[i * id.channels] == 1.0f) on_terrain += added, ++terrain;
  }
  EXPECT_GE(least, -1e-3) << "the shafts only add light (half precision)";
  EXPECT_GT(most - least, 0.05) << "streaks, not a uniform haze";
  ASSERT_GT(terrain, 0);
  EXPECT_GT(on_terrain / terrain, 0.005) << "light over the floor and the cliff";
}

TEST(DeepOcean, BenchSweepsTheCausticBlendShiftAndInterval) {
  const auto dir = aq::test::scratch_dir("deep_ocean_bench");
  const std::string err_path = (dir / "stderr.txt").string();
  const auto result = aq::test::run_command(
      "{ " + std::string(AQ_APP_PATH) + " bench " +
      aq::test::source_path("graphs/deep_ocean.json") +
      " --node caustics --size 64x36 --frames 1 --warmup 0 -q --json 2>" + err_path + "; }");
  std::stringstream errors;
  errors << std::ifstream(err_path).rdbuf();
  ASSERT_EQ(result.exit_code, 0) << errors.str();
  const auto report = nlohmann::json::parse(result.output, nullptr, false);
  ASSERT_TRUE(report.is_object()) << errors.str();
  const nlohmann::json* blend = nullptr;
  for (const auto& s : report["sweeps"]) {
    if (s["series"] == "caustics blend_count") blend = &s;
  }
  ASSERT_NE(blend, nullptr) << result.output;
  ASSERT_FALSE((*blend)["points"].empty());
  EXPECT_EQ((*blend)["points"].back()["mean_abs"].get<double>(), 0.0);   // the reference again
  EXPECT_GT((*blend)["points"].front()["mean_abs"].get<double>(), 0.0);  // one image differs
  // shift and blend_interval, each against the flux reference (CPU) with the same setting.
  for (const char* series : {"caustics shift", "caustics blend_interval"}) {
    const nlohmann::json* sweep = nullptr;
    for (const auto& s : report["sweeps"]) {
      if (s["series"] == series) sweep = &s;
    }
    ASSERT_NE(sweep, nullptr) << series << " missing from " << result.output;
    EXPECT_EQ((*sweep)["kind"], "cpu_reference");
    ASSERT_GE((*sweep)["points"].size(), 3u) << series;
    for (const auto& point : (*sweep)["points"]) {
      // The node on a 128 grid against the 512-grid flux: the estimator's error, not a
      // misplaced shift (0.1) or a wrong blend (the intervals' images differ by far more).
      EXPECT_LT(point["mean_abs"].get<double>(), 0.05) << series << " " << point;
    }
  }
}

// Every node and parameter issue 38 added is in the bench's speed-against-error report, each
// point timed and compared with its reference, the errors where the maths says they are.
TEST(DeepOcean, BenchSweepsEveryNewNodeAndParameter) {
  const auto dir = aq::test::scratch_dir("deep_ocean_bench_all");
  const std::string err_path = (dir / "stderr.txt").string();
  const auto result = aq::test::run_command(
      "{ " + std::string(AQ_APP_PATH) + " bench " +
      aq::test::source_path("graphs/deep_ocean.json") +
      " --node environment --node object --node light_shafts --size 64x36 --frames 1 "
      "--warmup 0 -q --json 2>" +
      err_path + "; }");
  std::stringstream errors;
  errors << std::ifstream(err_path).rdbuf();
  ASSERT_EQ(result.exit_code, 0) << errors.str();
  const auto report = nlohmann::json::parse(result.output, nullptr, false);
  ASSERT_TRUE(report.is_object()) << errors.str();
  std::map<std::string, nlohmann::json> sweeps;
  for (const auto& s : report["sweeps"]) sweeps[s["series"].get<std::string>()] = s;
  for (const char* series :
       {"environment", "object terrain_cells", "object swim_forward", "light_shafts steps"}) {
    ASSERT_TRUE(sweeps.count(series)) << series << " missing from " << result.output;
    ASSERT_FALSE(sweeps[series]["points"].empty()) << series;
    for (const auto& point : sweeps[series]["points"]) {
      EXPECT_TRUE(point["mean_abs"].is_number()) << series << " " << point;
      EXPECT_GT(point["time_ms"]["median"].get<double>(), 0.0) << series << " " << point;
    }
  }
  // The environment within a few thousandths (llvmpipe's atan/asin) up to 512 texels across.
  for (const auto& point : sweeps["environment"]["points"]) {
    if (point["setting"] == "panorama 4096x2048") continue;
    EXPECT_LT(point["max_abs"].get<double>(), 0.02) << point;
  }
  // A body built along any axis swims as the one built along +x.
  for (const auto& point : sweeps["object swim_forward"]["points"])
    EXPECT_LT(point["mean_abs"].get<double>(), 1e-4) << point;
  // Finer terrain grids and more shaft segments come closer to their references.
  const auto& terrain = sweeps["object terrain_cells"]["points"];
  EXPECT_GT(terrain.front()["mean_abs"].get<double>(), terrain[terrain.size() - 2]["mean_abs"]);
  EXPECT_EQ(terrain.back()["mean_abs"].get<double>(), 0.0);
  const auto& shafts = sweeps["light_shafts steps"]["points"];
  EXPECT_GT(shafts.front()["mean_abs"].get<double>(), shafts.back()["mean_abs"].get<double>());
}

}  // namespace
