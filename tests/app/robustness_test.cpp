// Faults seen from the command line (issue 8): broken images behind a `read` node, plugins
// that fail or whose shader does not compile, SIGINT/SIGTERM in the middle of a frame range,
// graphs that name code to load, and `read` paths relative to the graph file. Each case
// checks the exit code, that the message names the node (and parameter), and what is left
// on disk: only complete frames, no temporary files. Bad arguments are in cli_test.cpp.
#include <aquarelle/core/color.h>
#include <aquarelle/core/image_io.h>
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <fstream>
#include <thread>

#include "app/cli_support.h"
#include "support/harness.h"

namespace aq::test {
namespace {

namespace fs = std::filesystem;

void write_text(const fs::path& path, const std::string& text) {
  std::ofstream(path) << text;
}

std::string file_bytes(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), {});
}

void write_input(const fs::path& path, int width = 32, int height = 20) {
  auto written = write_image(path.string(), gradient_image(width, height), WriteOptions{true, 8});
  ASSERT_TRUE(written.ok()) << written.message();
}

// read(PATH) -> tint: the smallest graph that reads a file and runs a plugin.
std::string read_graph(const std::string& path, const std::string& frames = "[1, 1]") {
  return R"({
  "aquarelle": 1,
  "settings": {"width": 32, "height": 20, "frames": )" +
         frames + R"(, "precision": "float"},
  "nodes": {
    "source": {"type": "read", "params": {"path": ")" +
         path + R"("}},
    "tint": {"type": "tint", "params": {"amount": 0.5}, "inputs": {"image": "source.image"}}
  },
  "output": "tint.image"
})";
}

// The test plugins (test_fail, test_bad_shader...) come only through the plugin path.
std::string with_test_plugins(const std::string& arguments) {
  return "env AQUARELLE_PLUGIN_PATH=" + std::string(AQ_TEST_PLUGIN_DIR) + ":" +
         AQ_PLUGIN_BUILD_DIR + " " + AQ_APP_PATH + " " + arguments;
}

void expect_no_temporary_files(const fs::path& dir) {
  for (const auto& entry : fs::directory_iterator(dir)) {
    EXPECT_EQ(entry.path().filename().string().find(".tmp"), std::string::npos)
        << "temporary file left behind: " << entry.path();
  }
}

// Every frame file in `dir` reads back as a whole image of the render size.
int count_complete_frames(const fs::path& dir, const std::string& prefix) {
  auto config = ColorConfig::load();
  EXPECT_TRUE(config.ok()) << config.message();
  int complete = 0;
  for (const auto& entry : fs::directory_iterator(dir)) {
    const std::string name = entry.path().filename().string();
    if (name.rfind(prefix, 0) != 0) continue;
    auto image = read_image(entry.path().string(), *config);
    EXPECT_TRUE(image.ok()) << name << ": " << image.message();
    if (!image.ok()) continue;
    EXPECT_EQ(image->width, 32) << name;
    EXPECT_EQ(image->height, 20) << name;
    ++complete;
  }
  return complete;
}

struct BrokenImage {
  std::string name;
  std::string file;
  std::string says;  // part of the message besides the node and the parameter
};

TEST(Robustness, BrokenImagesBehindAReadNodeNameTheNodeAndParameter) {
  auto dir = scratch_dir("robustness_images");
  // Whole files to break.
  write_input(dir / "whole.png");
  write_input(dir / "whole.exr");
  fs::copy_file(dir / "whole.png", dir / "truncated.png");
  fs::resize_file(dir / "truncated.png", fs::file_size(dir / "whole.png") / 2);
  fs::copy_file(dir / "whole.exr", dir / "truncated.exr");
  fs::resize_file(dir / "truncated.exr", fs::file_size(dir / "whole.exr") / 2);
  write_text(dir / "empty.png", "");
  write_text(dir / "notes.txt", "not an image at all\n");
  // A header claiming 20000 x 20000 pixels with none following: refused before allocating.
  std::ofstream(dir / "huge.ppm", std::ios::binary) << "P6\n20000 20000\n255\n";
  // A header claiming zero pixels.
  std::ofstream(dir / "zero.ppm", std::ios::binary) << "P6\n0 0\n255\n";
  fs::create_directories(dir / "folder.png");

  const BrokenImage cases[] = {
      {"missing", "missing.png", "missing.png"},
      {"truncated png", "truncated.png", "truncated.png"},
      {"truncated exr", "truncated.exr", "truncated.exr"},
      {"empty file", "empty.png", "empty.png"},
      {"unsupported format", "notes.txt", "notes.txt"},
      {"huge dimensions", "huge.ppm", "16384"},
      {"zero size", "zero.ppm", "zero.ppm"},
      {"a folder", "folder.png", "folder.png"},
  };
  for (const auto& c : cases) {
    const fs::path graph = dir / ("graph_" + std::to_string(&c - cases) + ".json");
    write_text(graph, read_graph(c.file));
    const fs::path out = dir / ("out_" + std::to_string(&c - cases) + ".exr");
    auto result = aquarelle("render " + graph.string() + " -q -o " + out.string());
    EXPECT_EQ(result.exit_code, 1) << c.name << "\n" << result.output;
    EXPECT_NE(result.output.find("'source'"), std::string::npos) << c.name << "\n" << result.output;
    EXPECT_NE(result.output.find("'path'"), std::string::npos) << c.name << "\n" << result.output;
    EXPECT_NE(result.output.find(c.says), std::string::npos) << c.name << "\n" << result.output;
    EXPECT_FALSE(fs::exists(out)) << c.name << ": no output for a failed frame";
  }
  expect_no_temporary_files(dir);
}

TEST(Robustness, ReadPathsResolveRelativeToTheGraphFileNotTheWorkingDirectory) {
  auto dir = scratch_dir("robustness_relative");
  fs::create_directories(dir / "project" / "images");
  fs::create_directories(dir / "elsewhere");
  write_input(dir / "project" / "images" / "input.exr");
  write_text(dir / "project" / "graph.json", read_graph("images/input.exr"));
  write_text(dir / "project" / "missing.json", read_graph("images/nothere.exr"));
  // Run from another folder: the path must not be taken relative to it.
  const std::string cd = "cd " + (dir / "elsewhere").string() + " && ";
  auto good = run_command(cd + AQ_APP_PATH + " render ../project/graph.json -q -o out.exr");
  EXPECT_EQ(good.exit_code, 0) << good.output;
  EXPECT_TRUE(fs::exists(dir / "elsewhere" / "out.exr"));

  auto missing = run_command(cd + AQ_APP_PATH + " render ../project/missing.json -q -o m.exr");
  EXPECT_EQ(missing.exit_code, 1) << missing.output;
  EXPECT_NE(missing.output.find("'source'"), std::string::npos) << missing.output;
  // The message shows where it looked: next to the graph file.
  EXPECT_NE(missing.output.find("project/images/nothere.exr"), std::string::npos) << missing.output;
}

struct FaultCase {
  std::string type;
  std::string says;
};

class PluginFault : public ::testing::TestWithParam<FaultCase> {};

TEST_P(PluginFault, StopsTheRenderNamingTheNodeAndKeepsEarlierFrames) {
  const FaultCase& fault = GetParam();
  auto dir = scratch_dir("robustness_fault_" + fault.type);
  write_input(dir / "input.exr");
  const std::string pattern = (dir / "f_####.exr").string();
  // Frames 1-2 from a graph that works.
  write_text(dir / "good.json", read_graph("input.exr", "[1, 4]"));
  auto good =
      aquarelle("render " + (dir / "good.json").string() + " -q --frames 1-2 -o " + pattern);
  ASSERT_EQ(good.exit_code, 0) << good.output;
  const std::string frame1 = file_bytes(dir / "f_0001.exr");
  const std::string frame2 = file_bytes(dir / "f_0002.exr");

  // The same range finished by a graph whose plugin fails from frame 3 on.
  write_text(dir / "bad.json", R"({
  "aquarelle": 1,
  "settings": {"width": 32, "height": 20, "frames": [1, 4], "precision": "float"},
  "nodes": {
    "source": {"type": "read", "params": {"path": "input.exr"}},
    "faulty": {"type": ")" + fault.type +
                                   R"(", "inputs": {"image": "source.image"}}
  },
  "output": "faulty.image"
})");
  auto bad = run_command(
      with_test_plugins("render " + (dir / "bad.json").string() + " -q --resume -o " + pattern));
  EXPECT_EQ(bad.exit_code, 1) << bad.output;
  EXPECT_NE(bad.output.find("frame 3"), std::string::npos) << bad.output;
  EXPECT_NE(bad.output.find("'faulty'"), std::string::npos) << bad.output;
  EXPECT_NE(bad.output.find(fault.says), std::string::npos) << bad.output;
  EXPECT_EQ(file_bytes(dir / "f_0001.exr"), frame1) << "frame 1 untouched";
  EXPECT_EQ(file_bytes(dir / "f_0002.exr"), frame2) << "frame 2 untouched";
  EXPECT_FALSE(fs::exists(dir / "f_0003.exr")) << "no file for the failed frame";
  EXPECT_FALSE(fs::exists(dir / "f_0004.exr")) << "the render stopped at the failure";
  expect_no_temporary_files(dir);
}

INSTANTIATE_TEST_SUITE_P(Faults, PluginFault,
                         ::testing::Values(FaultCase{"test_fail", "this node always fails"},
                                           FaultCase{"test_bad_shader", "broken.frag"}),
                         [](const auto& info) { return info.param.type; });

// Starts `aquarelle ARGS...` as a child with its output in `log`; returns its pid.
pid_t spawn_aquarelle(const std::vector<std::string>& arguments, const fs::path& log) {
  pid_t pid = fork();
  if (pid == 0) {
    FILE* out = std::freopen(log.c_str(), "w", stdout);
    if (out == nullptr || dup2(fileno(stdout), STDERR_FILENO) < 0) _exit(127);
    std::vector<char*> argv;
    argv.push_back(const_cast<char*>(AQ_APP_PATH));
    for (const auto& argument : arguments) argv.push_back(const_cast<char*>(argument.c_str()));
    argv.push_back(nullptr);
    execv(AQ_APP_PATH, argv.data());
    _exit(127);
  }
  return pid;
}

int count_files(const fs::path& dir, const std::string& prefix) {
  int count = 0;
  for (const auto& entry : fs::directory_iterator(dir)) {
    if (entry.path().filename().string().rfind(prefix, 0) == 0) ++count;
  }
  return count;
}

class Interrupt : public ::testing::TestWithParam<int> {};

TEST_P(Interrupt, LeavesOnlyCompleteFramesAndResumeFinishesTheRange) {
  const int signal_number = GetParam();
  auto dir = scratch_dir("robustness_signal_" + std::to_string(signal_number));
  write_input(dir / "input.exr");
  constexpr int kFrames = 300;
  write_text(dir / "graph.json", read_graph("input.exr", "[1, 300]"));
  const std::string pattern = (dir / "f_####.exr").string();
  pid_t pid =
      spawn_aquarelle({"render", (dir / "graph.json").string(), "-o", pattern}, dir / "log.txt");
  ASSERT_GT(pid, 0);
  // Wait for the first frames, then interrupt mid-range.
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(60);
  int status = 0;
  bool exited_early = false;
  while (count_files(dir, "f_") < 3 && std::chrono::steady_clock::now() < deadline) {
    if (waitpid(pid, &status, WNOHANG) == pid) {
      exited_early = true;
      break;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(2));
  }
  if (!exited_early) {
    ASSERT_EQ(kill(pid, signal_number), 0);
    ASSERT_EQ(waitpid(pid, &status, 0), pid);
  }
  const std::string log = file_bytes(dir / "log.txt");
  ASSERT_FALSE(exited_early) << "aquarelle ended before the signal (status " << status << ")\n"
                             << log;
  ASSERT_TRUE(WIFEXITED(status)) << "killed instead of stopping cleanly\n" << log;
  ASSERT_EQ(WEXITSTATUS(status), 130) << "the range finished before the signal? " << log;
  EXPECT_NE(log.find("--resume"), std::string::npos) << log;

  const int complete = count_complete_frames(dir, "f_");
  EXPECT_GE(complete, 3);
  EXPECT_LT(complete, kFrames);
  expect_no_temporary_files(dir);

  auto resumed = aquarelle("render " + (dir / "graph.json").string() + " --resume -o " + pattern);
  ASSERT_EQ(resumed.exit_code, 0) << resumed.output;
  EXPECT_NE(resumed.output.find(std::to_string(complete) + " already there"), std::string::npos)
      << resumed.output;
  EXPECT_EQ(count_complete_frames(dir, "f_"), kFrames);
  expect_no_temporary_files(dir);
}

INSTANTIATE_TEST_SUITE_P(Signals, Interrupt, ::testing::Values(SIGINT, SIGTERM),
                         [](const auto& info) { return std::string(strsignal(info.param)); });

// A graph names code in every place one might try: as a node type, as a top-level key, in
// the editor's free-form block and as a parameter. None of it may be loaded: glibc's
// LD_DEBUG=files lists every library the process opens.
TEST(Robustness, AGraphNeverLoadsCodeFromAPathItNames) {
  auto dir = scratch_dir("robustness_no_code");
  write_input(dir / "input.exr");
  const std::string library = std::string(AQ_TEST_PLUGIN_DIR) + "/aquarelle_test_nodes.so";
  ASSERT_TRUE(fs::exists(library));
  write_text(dir / "as_type.json", R"({
  "aquarelle": 1,
  "plugins": [")" + library + R"("],
  "settings": {"width": 32, "height": 20},
  "nodes": {
    "source": {"type": "read", "params": {"path": "input.exr"}},
    "evil": {"type": ")" + library + R"(", "inputs": {"image": "source.image"}}
  },
  "output": "evil.image",
  "editor": {"plugin": ")" + library + R"("}
})");
  write_text(dir / "as_path.json", read_graph(library));
  struct Case {
    const char* file;
    const char* command;
    int exit_code;  // the path as a `read` parameter is only data: validate opens it as an
                    // image (OpenImageIO reads its header), finds none, and says so
  };
  const Case cases[] = {{"as_type.json", "validate", 1},
                        {"as_type.json", "render", 1},
                        {"as_path.json", "validate", 1},
                        {"as_path.json", "render", 1}};
  for (const Case& c : cases) {
    std::string arguments = std::string(c.command) + " " + (dir / c.file).string();
    if (std::string(c.command) == "render") arguments += " -q -o " + (dir / "out.exr").string();
    auto result = run_command("env LD_DEBUG=files " + std::string(AQ_APP_PATH) + " " + arguments);
    EXPECT_EQ(result.exit_code, c.exit_code) << arguments << "\n" << result.output.substr(0, 4000);
    EXPECT_EQ(result.output.find("file=" + library), std::string::npos)
        << arguments << ": the graph made the process open " << library;
    // LD_DEBUG works here at all: the build's own plugins show up.
    EXPECT_NE(result.output.find("file=" + std::string(AQ_PLUGIN_BUILD_DIR)), std::string::npos)
        << arguments;
  }
  EXPECT_FALSE(fs::exists(dir / "out.exr"));
}

}  // namespace
}  // namespace aq::test
