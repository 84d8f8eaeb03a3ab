// Round three (issue 40), class 3: nothing waits forever. A FIFO (or a link to a device) named
// *.so among the plugins is refused before dlopen, for every command that loads plugins; a
// frame range at the top of `int` is refused by `validate` and the renderer alike instead of
// wrapping and writing files forever. A property test throws random folder contents at the
// plugin scan: it always returns, refusing every candidate that is not a loadable plugin.
#include <aquarelle/core/graph_io.h>
#include <aquarelle/core/plugin_loader.h>

#include <climits>
#include <random>
#include <utility>

#include "bad_input/bad_input_support.h"

namespace aq::test::bad_input {
namespace {

bool mentions(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}

TEST(Hangs, FifoNamedSoInThePluginPathIsRefusedByEveryCommand) {
  const fs::path dir = scratch_dir("bad_input_plugin_fifo");
  make_fifo(dir / "aaa_fifo.so");
  const std::string environment =
      "AQUARELLE_PLUGIN_PATH=" + dir.string() + ":" + AQ_PLUGIN_BUILD_DIR;
  write_bytes(dir / "g.json", R"({"aquarelle": 1,
  "settings": {"width": 8, "height": 8, "frames": [1, 1]},
  "nodes": {"model": {"type": "scene", "params": {"preset": "cube"}},
            "gbuf": {"type": "gbuffer", "inputs": {"scene": "model.scene"}}},
  "output": "gbuf.albedo"})");
  for (const std::string& command : std::vector<std::string>{
           "nodes", "validate " + (dir / "g.json").string(),
           "render " + (dir / "g.json").string() + " -o " + (dir / "out.exr").string()}) {
    auto result = aquarelle_within(60, command, environment);
    EXPECT_NE(result.exit_code, 124) << command << " hung";
    if (command == "nodes") {
      EXPECT_TRUE(mentions(result.output, "aaa_fifo.so")) << command << ": " << result.output;
    }
  }
}

TEST(Hangs, FrameRangeAtTheTopOfIntIsRefused) {
  EXPECT_NE(frame_range_problem(INT_MAX - 10, INT_MAX), "");
  EXPECT_NE(frame_range_problem(INT_MIN, INT_MIN + 1), "");
  EXPECT_NE(frame_range_problem(-kMaxFrameNumber, kMaxFrameNumber), "");  // too many frames
  EXPECT_EQ(frame_range_problem(1, 240), "");
  const fs::path dir = scratch_dir("bad_input_frames_top");
  write_bytes(dir / "g.json", R"({"aquarelle": 1,
  "settings": {"width": 8, "height": 8, "frames": [2147483600, 2147483647]},
  "nodes": {"model": {"type": "scene", "params": {"preset": "cube"}},
            "gbuf": {"type": "gbuffer", "inputs": {"scene": "model.scene"}}},
  "output": "gbuf.albedo"})");
  auto validate = aquarelle_within(30, "validate " + (dir / "g.json").string());
  EXPECT_EQ(validate.exit_code, 1) << validate.output;
  EXPECT_TRUE(mentions(validate.output, "frames")) << validate.output;
  auto render = aquarelle_within(
      30, "render " + (dir / "g.json").string() + " -q -o " + (dir / "f####.exr").string());
  EXPECT_EQ(render.exit_code, 1) << render.output;
  write_bytes(dir / "ok.json",
              file_bytes(dir / "g.json")
                  .replace(file_bytes(dir / "g.json").find("[2147483600"), 24, "[1, 1]"));
  auto option = aquarelle_within(30, "render " + (dir / "ok.json").string() +
                                         " --frames 999999990-999999999 -q -o " +
                                         (dir / "f####.exr").string());
  EXPECT_EQ(option.exit_code, 1) << option.output;
  EXPECT_TRUE(mentions(option.output, "--frames")) << option.output;
  size_t written = 0;
  for (const auto& entry : fs::directory_iterator(dir))
    written += entry.path().extension() == ".exr";
  EXPECT_EQ(written, 0u);
}

// A chain of `count` nodes of `type` after the cube's g-buffer.
std::string chain_graph(int count, const std::string& type) {
  nlohmann::json nodes = {{"model", {{"type", "scene"}, {"params", {{"preset", "cube"}}}}},
                          {"gbuf", {{"type", "gbuffer"}, {"inputs", {{"scene", "model.scene"}}}}}};
  std::string previous = "gbuf.albedo";
  for (int i = 0; i < count; ++i) {
    const std::string id = "n" + std::to_string(i);
    nodes[id] = {{"type", type}, {"inputs", {{"image", previous}}}};
    previous = id + ".image";
  }
  nlohmann::json graph = {{"aquarelle", 1},
                          {"settings", {{"width", 16}, {"height", 16}, {"frames", {1, 1}}}},
                          {"nodes", nodes},
                          {"output", previous}};
  return graph.dump();
}

// 20,000 `erode` nodes in a chain ran for 151 s (1,000: 4 s): refused by `validate` and
// `render` alike, in seconds, naming the limit. A chain at the limit still renders.
TEST(Hangs, TwentyThousandNodeChainIsRefusedInSeconds) {
  const fs::path dir = scratch_dir("bad_input_long_chain");
  write_bytes(dir / "long.json", chain_graph(20000, "erode"));
  for (const std::string& command :
       {"validate " + (dir / "long.json").string(),
        "render " + (dir / "long.json").string() + " -q -o " + (dir / "out.exr").string()}) {
    const MeasuredRun run = aquarelle_measured(60, command);
    EXPECT_EQ(run.exit_code, 1) << command << ": " << run.output.substr(0, 2000);
    EXPECT_TRUE(mentions(run.output, "more than 1000 nodes")) << run.output.substr(0, 2000);
    EXPECT_LT(run.seconds, 20.0) << command;
  }
  EXPECT_FALSE(fs::exists(dir / "out.exr"));
  write_bytes(dir / "limit.json", chain_graph(static_cast<int>(kMaxGraphNodes) - 2, "tint"));
  auto at_limit = aquarelle_within(
      120, "render " + (dir / "limit.json").string() + " -q -o " + (dir / "out.exr").string());
  EXPECT_EQ(at_limit.exit_code, 0) << at_limit.output.substr(0, 2000);
}

// A 200 GB sparse file named .png or .obj (no disk used) is refused by its size before any
// format probe reads it: the probe used to read it whole.
TEST(Hangs, SparseFileOf200GigabytesIsRefusedBeforeAProbeReadsIt) {
  const fs::path dir = scratch_dir("bad_input_sparse_200g");
  for (const char* name : {"huge.png", "huge.obj"}) {
    std::error_code error;
    write_bytes(dir / name, "");
    fs::resize_file(dir / name, 200ull << 30, error);
    if (error) GTEST_SKIP() << "this file system cannot hold a 200 GB sparse file: " << error;
  }
  write_bytes(dir / "image.json", R"({"aquarelle": 1,
  "settings": {"width": 8, "height": 8, "frames": [1, 1]},
  "nodes": {"source": {"type": "read", "params": {"path": "huge.png"}}},
  "output": "source.image"})");
  write_bytes(dir / "mesh.json", mesh_graph("huge.obj"));
  for (const auto& [graph, file] :
       {std::pair{"image.json", "huge.png"}, {"mesh.json", "huge.obj"}}) {
    // `validate` does not open meshes; it probes images.
    for (const std::string command : {"validate", "render"}) {
      if (command == "validate" && std::string(file) == "huge.obj") continue;
      const MeasuredRun run = aquarelle_measured(
          60, command + " " + (dir / graph).string() +
                  (command == "render" ? " -q -o " + (dir / "out.exr").string() : ""));
      EXPECT_EQ(run.exit_code, 1) << command << " " << graph << ": " << run.output;
      EXPECT_TRUE(mentions(run.output, file)) << run.output;
      EXPECT_TRUE(mentions(run.output, "memory budget")) << run.output;
      EXPECT_LT(run.seconds, 20.0) << command << " " << graph;
      EXPECT_LT(run.peak_kib, 1000L * 1000L) << command << " " << graph;
    }
  }
}

// Random folders of hostile plugin candidates: FIFOs, folders, links to devices, to nothing and
// to themselves, empty and garbage files, an ELF header cut short, all named *.so.
TEST(PluginScanProperty, RandomFoldersAlwaysReturnAndRefuseEveryBadCandidate) {
  std::mt19937 random(40);
  for (int round = 0; round < 12; ++round) {
    const fs::path dir = scratch_dir("bad_input_plugin_scan_" + std::to_string(round));
    int made = 0;
    for (int i = 0; i < 8; ++i) {
      const fs::path name = dir / ("c" + std::to_string(i) + ".so");
      switch (random() % 8) {
        case 0:
          make_fifo(name);
          break;
        case 1:
          fs::create_directory(name);
          break;
        case 2:
          fs::create_symlink("/dev/zero", name);
          break;
        case 3:
          fs::create_symlink(dir / "missing", name);
          break;
        case 4:
          fs::create_symlink(name, name);
          break;
        case 5:
          write_bytes(name, "");
          break;
        case 6:
          write_bytes(name, std::string("\x7f"
                                        "ELF\x02\x01\x01",
                                        7));
          break;
        default: {
          std::string bytes(random() % 4096, '\0');
          for (char& c : bytes) c = static_cast<char>(random());
          write_bytes(name, bytes);
        }
      }
      ++made;
    }
    Registry registry;
    PluginSet plugins;
    const PluginLoadReport report = plugins.load({dir.string()}, registry);
    EXPECT_TRUE(report.loaded.empty()) << "round " << round;
    EXPECT_EQ(static_cast<int>(report.refused.size()), made) << "round " << round;
  }
}

}  // namespace
}  // namespace aq::test::bad_input
