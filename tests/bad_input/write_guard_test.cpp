// Round three (issue 40), class 1: no writer destroys an input. One rule, aq::check_may_write,
// for -o, --layer's side file, `bench --csv/--plot`, the editor's --screenshot and Save As, and
// the Python module (tested in
// test_python_bad_input.py): never onto a file the evaluation reads, resolved through links
// (a texture an OBJ's MTL names included), never onto something that is not a regular file.
#include <aquarelle/core/graph_io.h>
#include <aquarelle/core/image_io.h>
#include <aquarelle/core/write_guard.h>

#include "bad_input/bad_input_support.h"
#include "editor/window_fixture.h"

namespace aq::test::bad_input {
namespace {

bool mentions(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}

// An OBJ whose MTL names a texture: the texture is a file the graph reads.
fs::path textured_obj(const fs::path& dir) {
  write_bytes(dir / "tri.obj",
              "mtllib tri.mtl\nv -1 -1 0\nv 1 -1 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 0 1\n"
              "usemtl paint\nf 1/1 2/2 3/3\n");
  write_bytes(dir / "tri.mtl", "newmtl paint\nKd 1 1 1\nmap_Kd -bm 1.0 tex.png\n");
  EXPECT_TRUE(write_image((dir / "tex.png").string(), gradient_image(8, 8)).ok());
  const fs::path graph = dir / "g.json";
  write_bytes(graph, mesh_graph("tri.obj"));
  return graph;
}

TEST(WriteGuard, TheTextureAnObjsMaterialNamesIsAnInput) {
  const fs::path dir = scratch_dir("bad_input_guard_mtl");
  const fs::path graph_file = textured_obj(dir);
  ReadResult read = read_graph_file(graph_file.string(), registry());
  ASSERT_TRUE(read.ok()) << format_problems(read.problems);
  const auto reads = files_read_by(read.graph, registry());
  fs::create_symlink(dir / "tex.png", dir / "link.png");
  for (const char* name : {"tex.png", "link.png", "tri.mtl", "tri.obj", "g.json"}) {
    auto s = check_may_write("-o", (dir / name).string(), reads);
    EXPECT_FALSE(s.ok()) << name;
  }
  EXPECT_TRUE(check_may_write("-o", (dir / "out.png").string(), reads).ok());
}

TEST(WriteGuard, RenderRefusesAnOutputThatIsAMaterialsTexture) {
  const fs::path dir = scratch_dir("bad_input_guard_mtl_cli");
  const fs::path graph_file = textured_obj(dir);
  const std::string before = file_bytes(dir / "tex.png");
  fs::create_hard_link(dir / "tex.png", dir / "hard.png");
  for (const std::string out : {"tex.png", "hard.png"}) {
    auto result =
        aquarelle_within(60, "render " + graph_file.string() + " -q -o " + (dir / out).string());
    EXPECT_EQ(result.exit_code, 1) << out << ": " << result.output;
    EXPECT_TRUE(mentions(result.output, "tex.png")) << result.output;
  }
  EXPECT_EQ(file_bytes(dir / "tex.png"), before) << "the texture was overwritten";
}

TEST(WriteGuard, LayerSideFileThatIsAnInputIsRefused) {
  const fs::path dir = scratch_dir("bad_input_guard_layers");
  ASSERT_TRUE(write_image((dir / "out.layers.exr").string(), gradient_image(8, 8)).ok());
  const std::string before = file_bytes(dir / "out.layers.exr");
  write_bytes(dir / "g.json", R"({"aquarelle": 1,
  "settings": {"width": 8, "height": 8, "frames": [1, 1]},
  "nodes": {"source": {"type": "read", "params": {"path": "out.layers.exr"}},
            "tint": {"type": "tint", "inputs": {"image": "source.image"}}},
  "output": "tint.image"})");
  auto result =
      aquarelle_within(60, "render " + (dir / "g.json").string() + " -q --layer source.image -o " +
                               (dir / "out.png").string());
  EXPECT_EQ(result.exit_code, 1) << result.output;
  EXPECT_TRUE(mentions(result.output, "--layer")) << result.output;
  EXPECT_EQ(file_bytes(dir / "out.layers.exr"), before) << "the input was overwritten";
}

TEST(WriteGuard, BenchCsvOrPlotOntoTheGraphIsRefusedBeforeMeasuring) {
  const fs::path dir = scratch_dir("bad_input_guard_bench");
  const std::string graph = file_bytes(source_path("graphs/underwater.json"));
  write_bytes(dir / "g.json", graph);
  for (const std::string option : {"--csv", "--plot"}) {
    auto result = aquarelle_within(60, "bench " + (dir / "g.json").string() + " -q " + option +
                                           " " + (dir / "g.json").string());
    EXPECT_EQ(result.exit_code, 1) << option << ": " << result.output;
    EXPECT_TRUE(mentions(result.output, "is the graph file")) << result.output;
  }
  EXPECT_EQ(file_bytes(dir / "g.json"), graph) << "bench replaced the graph";
}

// Class 3: a FIFO as an output or a report blocks the writer or reader; a folder threw.
TEST(WriteGuard, FifoOutputsAreRefusedAtOnce) {
  const fs::path dir = scratch_dir("bad_input_guard_fifo");
  write_bytes(dir / "g.json", R"({"aquarelle": 1,
  "settings": {"width": 8, "height": 8, "frames": [1, 1]},
  "nodes": {"model": {"type": "scene", "params": {"preset": "cube"}},
            "gbuf": {"type": "gbuffer", "inputs": {"scene": "model.scene"}}},
  "output": "gbuf.albedo"})");
  const fs::path fifo = make_fifo(dir / "out.png");
  auto render =
      aquarelle_within(30, "render " + (dir / "g.json").string() + " -q -o " + fifo.string());
  EXPECT_EQ(render.exit_code, 1) << render.output;
  EXPECT_TRUE(mentions(render.output, "FIFO")) << render.output;
  auto bench =
      aquarelle_within(30, "bench " + (dir / "g.json").string() + " -q --csv " + fifo.string());
  EXPECT_EQ(bench.exit_code, 1) << bench.output;
  EXPECT_TRUE(mentions(bench.output, "FIFO")) << bench.output;
}

TEST(WriteGuard, PlotFromAFifoOrAFolderIsExitOne) {
  const fs::path dir = scratch_dir("bad_input_guard_plot_from");
  const fs::path fifo = make_fifo(dir / "report.json");
  for (const fs::path& report : {fifo, dir}) {
    auto result = aquarelle_within(
        30, "bench --plot-from " + report.string() + " --plot " + (dir / "plot.png").string());
    EXPECT_EQ(result.exit_code, 1) << report << ": " << result.output;
    EXPECT_TRUE(mentions(result.output, "--plot-from")) << result.output;
  }
}

// The editor writes too: `--screenshot` onto an image the graph reads or onto the graph, and
// Save As onto the image, each wrote over the input (the window's pixels, the graph's JSON).
class EditorWrites : public aq::test::EditorWindowTest {};

TEST_F(EditorWrites, ScreenshotAndSaveAsNeverWriteOntoAnInput) {
  ASSERT_TRUE(write_image((dir_ / "input.png").string(), gradient_image(8, 8)).ok());
  write_bytes(dir_ / "graph.json", R"({"aquarelle": 1,
  "settings": {"width": 32, "height": 32, "frames": [1, 1]},
  "nodes": {"source": {"type": "read", "params": {"path": "input.png"}}},
  "output": "source.image"})");
  const std::string image = file_bytes(dir_ / "input.png");
  const std::string graph = file_bytes(dir_ / "graph.json");
  write_bytes(dir_ / "none.json", "[]");
  write_bytes(dir_ / "save.json", R"([{"do": "save", "path": "input.png", "replace": true}])");
  struct Case {
    std::string args, names;
  };
  for (const Case& c : {Case{"--script none.json --screenshot input.png", "--screenshot"},
                        Case{"--script none.json --screenshot graph.json", "--screenshot"},
                        Case{"--script save.json --screenshot shot.png", "Save As"}}) {
    std::string log;
    EXPECT_EQ(run_editor("graph.json " + c.args + " --quit --size 640x400", &log), 1) << log;
    EXPECT_TRUE(mentions(log, c.names)) << log;
    EXPECT_TRUE(file_bytes(dir_ / "input.png") == image) << "input.png overwritten: " << c.args;
    EXPECT_TRUE(file_bytes(dir_ / "graph.json") == graph) << "graph.json overwritten: " << c.args;
  }
}

}  // namespace
}  // namespace aq::test::bad_input
