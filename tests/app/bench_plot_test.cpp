// The bench's plot (PLplot): redrawn from a saved report with --plot-from, one panel per node
// type laid out four to a row, in PNG, SVG or PDF, and clear refusals.
#include <gtest/gtest.h>

#include <fstream>
#include <nlohmann/json.hpp>

#include "app/cli_support.h"
#include "support/harness.h"

namespace aq::test {
namespace {

// Width and height from a PNG's IHDR chunk.
std::pair<int, int> png_size(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  unsigned char header[24] = {};
  in.read(reinterpret_cast<char*>(header), sizeof(header));
  if (std::string(reinterpret_cast<char*>(header) + 1, 3) != "PNG") return {0, 0};
  auto be32 = [&](int at) {
    return header[at] << 24 | header[at + 1] << 16 | header[at + 2] << 8 | header[at + 3];
  };
  return {be32(16), be32(20)};
}

// A report with `nodes` node types, each with one sweep of three points (one exact).
std::string write_report(const std::filesystem::path& dir, int nodes) {
  nlohmann::json report = {{"graph", "test.json"}, {"size", {64, 36}}, {"precision", "half"}};
  report["sweeps"] = nlohmann::json::array();
  for (int n = 0; n < nodes; ++n) {
    nlohmann::json sweep = {{"series", "node" + std::to_string(n) + " sweep"},
                            {"node", "node" + std::to_string(n)}};
    sweep["points"] = {{{"setting", "a"}, {"time_ms", {{"median", 1.0}}}, {"mean_abs", 0.1}},
                       {{"setting", "b"}, {"time_ms", {{"median", 3.0}}}, {"mean_abs", 0.01}},
                       {{"setting", "c"}, {"time_ms", {{"median", 9.0}}}, {"mean_abs", 0.0}}};
    report["sweeps"].push_back(sweep);
  }
  const auto path = dir / ("report" + std::to_string(nodes) + ".json");
  std::ofstream(path) << report.dump();
  return path.string();
}

TEST(BenchPlot, OnePanelPerNodeTypeFourToARow) {
  const auto dir = scratch_dir("bench_plot");
  for (auto [nodes, columns, rows] : {std::tuple{1, 2, 1}, {4, 4, 1}, {10, 4, 3}}) {
    const std::string png = (dir / ("plot" + std::to_string(nodes) + ".png")).string();
    auto run = aquarelle("bench --plot-from " + write_report(dir, nodes) + " --plot " + png);
    ASSERT_EQ(run.exit_code, 0) << run.output;
    auto [width, height] = png_size(png);
    EXPECT_EQ(width, columns * 340) << nodes << " panels";
    EXPECT_EQ(height, rows * 270 + 60) << nodes << " panels";
  }
  // Sweeps of one node type share its panel.
  nlohmann::json report = nlohmann::json::parse(std::ifstream(write_report(dir, 4)));
  for (auto& sweep : report["sweeps"]) sweep["node"] = "blur";
  std::ofstream(dir / "shared.json") << report.dump();
  const std::string shared = (dir / "shared.png").string();
  ASSERT_EQ(aquarelle("bench --plot-from " + (dir / "shared.json").string() + " --plot " + shared)
                .exit_code,
            0);
  EXPECT_EQ(png_size(shared), std::make_pair(2 * 340, 270 + 60));
}

TEST(BenchPlot, SvgAndPdfByExtension) {
  const auto dir = scratch_dir("bench_plot_formats");
  const std::string report = write_report(dir, 2);
  ASSERT_EQ(
      aquarelle("bench --plot-from " + report + " --plot " + (dir / "p.svg").string()).exit_code,
      0);
  ASSERT_EQ(
      aquarelle("bench --plot-from " + report + " --plot " + (dir / "p.pdf").string()).exit_code,
      0);
  std::ifstream svg(dir / "p.svg"), pdf(dir / "p.pdf");
  std::string svg_text((std::istreambuf_iterator<char>(svg)), {}), pdf_head(4, '\0');
  pdf.read(pdf_head.data(), 4);
  EXPECT_NE(svg_text.find("<svg"), std::string::npos);
  EXPECT_EQ(pdf_head, "%PDF");
}

TEST(BenchPlot, RefusalsSayWhatToDo) {
  const auto dir = scratch_dir("bench_plot_bad");
  const std::string report = write_report(dir, 1);
  auto extension = aquarelle("bench --plot-from " + report + " --plot " + (dir / "p.gif").string());
  EXPECT_EQ(extension.exit_code, 1);
  EXPECT_NE(extension.output.find("use a .png, .svg or .pdf"), std::string::npos);
  auto folder = aquarelle("bench --plot-from " + report + " --plot " + (dir / "no/p.png").string());
  EXPECT_EQ(folder.exit_code, 1);
  EXPECT_NE(folder.output.find("does the folder exist"), std::string::npos) << folder.output;
  auto no_plot = aquarelle("bench --plot-from " + report);
  EXPECT_EQ(no_plot.exit_code, 1);
  EXPECT_NE(no_plot.output.find("needs --plot"), std::string::npos);
  std::ofstream(dir / "not.json") << "{\"graph\": 1}";
  auto not_report = aquarelle("bench --plot-from " + (dir / "not.json").string() + " --plot " +
                              (dir / "p.png").string());
  EXPECT_EQ(not_report.exit_code, 1);
  EXPECT_NE(not_report.output.find("no \"sweeps\""), std::string::npos) << not_report.output;
  EXPECT_FALSE(std::filesystem::exists(dir / "p.png"));
}

}  // namespace
}  // namespace aq::test
