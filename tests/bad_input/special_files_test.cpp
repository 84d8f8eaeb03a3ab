// Special files where a file is expected (issue 17, item 3): a FIFO, /dev/zero or
// /dev/urandom as the graph file, a `read` path, a scene file, an OBJ's mtllib or $OCIO is
// refused at once (before: a hang that only SIGKILL stopped, or memory growing at 200 MB/s);
// and SIGINT/SIGTERM stop a render inside a long node within the grace period.
#include <aquarelle/core/color.h>
#include <aquarelle/core/graph_io.h>
#include <aquarelle/core/image_io.h>
#include <fcntl.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdlib>
#include <thread>
#include <vector>

#include "bad_input/bad_input_support.h"

namespace aq::test::bad_input {
namespace {

std::vector<std::string> special_paths(const fs::path& dir) {
  return {make_fifo(dir / "fifo").string(), "/dev/zero", "/dev/urandom"};
}

TEST(SpecialFiles, GraphFileMustBeRegular) {
  const fs::path dir = scratch_dir("bad_input_special_graph");
  for (const auto& path : special_paths(dir)) {
    ReadResult read = read_graph_file(path, registry());
    ASSERT_FALSE(read.ok()) << path;
    EXPECT_NE(read.problems[0].message.find("only regular files"), std::string::npos)
        << path << ": " << read.problems[0].message;
  }
}

TEST(SpecialFiles, ImagePathMustBeRegular) {
  const fs::path dir = scratch_dir("bad_input_special_image");
  auto config = ColorConfig::load();
  ASSERT_TRUE(config.ok()) << config.message();
  for (const auto& path : special_paths(dir)) {
    auto image = read_image(path, *config);
    ASSERT_FALSE(image.ok()) << path;
    EXPECT_NE(image.message().find(path), std::string::npos) << image.message();
    EXPECT_NE(image.message().find("only regular files"), std::string::npos) << image.message();
  }
}

TEST(SpecialFiles, SceneFileMustBeRegular) {
  const fs::path dir = scratch_dir("bad_input_special_scene");
  for (const auto& path : special_paths(dir)) {
    RenderOptions options;
    options.output = "gbuf.albedo";
    auto image = render_graph(mesh_graph(path), options);
    ASSERT_FALSE(image.ok()) << path;
    EXPECT_NE(image.message().find("only regular files"), std::string::npos) << image.message();
  }
}

TEST(SpecialFiles, MtllibMustBeRegular) {
  const fs::path dir = scratch_dir("bad_input_special_mtl");
  make_fifo(dir / "pipe.mtl");
  write_bytes(dir / "tri.obj", "mtllib pipe.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
  auto image = load_mesh(dir / "tri.obj");
  ASSERT_FALSE(image.ok());
  EXPECT_NE(image.message().find("pipe.mtl"), std::string::npos) << image.message();
  EXPECT_NE(image.message().find("FIFO"), std::string::npos) << image.message();
}

TEST(SpecialFiles, OcioConfigMustBeRegular) {
  const fs::path dir = scratch_dir("bad_input_special_ocio");
  const char* saved = std::getenv("OCIO");
  const std::string restore = saved != nullptr ? saved : "";
  for (const auto& path : special_paths(dir)) {
    ::setenv("OCIO", path.c_str(), 1);
    auto config = ColorConfig::load();
    ASSERT_FALSE(config.ok()) << path;
    EXPECT_NE(config.message().find("$OCIO"), std::string::npos) << config.message();
    EXPECT_NE(config.message().find("only regular files"), std::string::npos) << config.message();
  }
  if (saved != nullptr) {
    ::setenv("OCIO", restore.c_str(), 1);
  } else {
    ::unsetenv("OCIO");
  }
}

// A LUT named inside the config is opened by OCIO only when a transform needs it, where a FIFO
// would block: it is checked when the config loads. A regular LUT file loads as before.
TEST(SpecialFiles, OcioLutFilesMustBeRegular) {
  const fs::path dir = scratch_dir("bad_input_special_ocio_lut");
  auto config_with_lut = [&](const std::string& lut) {
    const fs::path path = dir / ("config_" + lut + ".ocio");
    write_bytes(path,
                "ocio_profile_version: 2.1\n"
                "search_path: \".\"\n"
                "roles:\n  default: raw\n  scene_linear: raw\n  reference: raw\n"
                "displays:\n  sRGB:\n    - !<View> {name: Raw, colorspace: raw}\n"
                "colorspaces:\n"
                "  - !<ColorSpace>\n    name: raw\n    isdata: true\n"
                "  - !<ColorSpace>\n    name: graded\n"
                "    from_scene_reference: !<GroupTransform>\n      children:\n"
                "        - !<FileTransform> {src: " +
                    lut + ", interpolation: linear}\n");
    return path;
  };
  write_bytes(dir / "curve.spi1d",
              "Version 1\nFrom 0.0 1.0\nLength 2\nComponents 1\n{\n0.0\n1.0\n}\n");
  make_fifo(dir / "pipe.spi1d");

  auto fine = ColorConfig::load_file(config_with_lut("curve.spi1d").string());
  ASSERT_TRUE(fine.ok()) << fine.message();
  auto fifo = ColorConfig::load_file(config_with_lut("pipe.spi1d").string());
  ASSERT_FALSE(fifo.ok());
  EXPECT_NE(fifo.message().find("pipe.spi1d"), std::string::npos) << fifo.message();
  EXPECT_NE(fifo.message().find("FIFO"), std::string::npos) << fifo.message();
  auto device = ColorConfig::load_file(config_with_lut("/dev/zero").string());
  ASSERT_FALSE(device.ok());
  EXPECT_NE(device.message().find("/dev/zero"), std::string::npos) << device.message();
}

TEST(SpecialFiles, RenderOfAFifoGraphEndsWithExitOne) {
  const fs::path dir = scratch_dir("bad_input_special_cli");
  const fs::path fifo = make_fifo(dir / "graph.json");
  auto render =
      aquarelle_within(60, "render " + fifo.string() + " -o " + (dir / "out.png").string() + " -q");
  EXPECT_EQ(render.exit_code, 1) << render.output;
  EXPECT_NE(render.output.find("FIFO"), std::string::npos) << render.output;
}

// A node that spins for 60 s: SIGTERM/SIGINT end the render with 130 long before it returns.
void expect_prompt_stop(int signal) {
  const fs::path dir = scratch_dir("bad_input_signal_" + std::to_string(signal));
  write_bytes(dir / "slow.json", R"({
  "aquarelle": 1,
  "settings": {"width": 16, "height": 16, "frames": [1, 1]},
  "nodes": {"slow": {"type": "test_slow", "params": {"seconds": 60}}},
  "output": "slow.image"
})");
  const std::string log = (dir / "log.txt").string();
  // Everything the child needs is made before fork: the test process has GL driver threads.
  const std::string plugins = "AQUARELLE_PLUGIN_PATH=" + hostile_plugin_path();
  std::vector<char*> environment;
  for (char** e = environ; *e != nullptr; ++e) {
    if (std::string(*e).rfind("AQUARELLE_PLUGIN_PATH=", 0) != 0) environment.push_back(*e);
  }
  environment.push_back(const_cast<char*>(plugins.c_str()));
  environment.push_back(nullptr);
  const std::string graph = (dir / "slow.json").string(), out = (dir / "out.exr").string();
  const char* argv[] = {AQ_APP_PATH, "render", graph.c_str(), "-o", out.c_str(), nullptr};
  const int log_fd = ::open(log.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  ASSERT_GE(log_fd, 0);
  const pid_t child = ::fork();
  ASSERT_GE(child, 0);
  if (child == 0) {
    ::dup2(log_fd, STDERR_FILENO);
    ::execve(AQ_APP_PATH, const_cast<char* const*>(argv), environment.data());
    ::_exit(98);
  }
  ::close(log_fd);
  // Wait until the render is inside the slow node (the context line is printed just before).
  for (int i = 0; i < 600 && file_bytes(log).find("aquarelle: OpenGL") == std::string::npos; ++i) {
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
  }
  std::this_thread::sleep_for(std::chrono::milliseconds(300));
  ::kill(child, signal);
  // Far less than the node's 60 s; the grace period is 1 s. Not a speed test: a render that
  // waited for the node would still be running when this gives up and kills it.
  int status = 0;
  pid_t done = 0;
  for (int i = 0; i < 200 && done == 0; ++i) {
    done = ::waitpid(child, &status, WNOHANG);
    if (done == 0) std::this_thread::sleep_for(std::chrono::milliseconds(50));
  }
  if (done == 0) {
    ::kill(child, SIGKILL);
    ::waitpid(child, &status, 0);
    FAIL() << "the render did not stop within 10 s of the signal; log:\n" << file_bytes(log);
  }
  ASSERT_TRUE(WIFEXITED(status)) << "ended by signal " << WTERMSIG(status);
  EXPECT_EQ(WEXITSTATUS(status), 130) << file_bytes(log);
  EXPECT_NE(file_bytes(log).find("--resume"), std::string::npos) << file_bytes(log);
  EXPECT_FALSE(fs::exists(dir / "out.exr"));
}

TEST(Signals, SigtermStopsARenderInsideALongNode) {
  expect_prompt_stop(SIGTERM);
}

TEST(Signals, SigintStopsARenderInsideALongNode) {
  expect_prompt_stop(SIGINT);
}

// The editor read its graph, its script and its autosave with a plain ifstream: a FIFO as any
// of them left the window waiting for ever. Each is refused at once with exit 1.
TEST(SpecialFiles, EditorGraphAndScriptMustBeRegular) {
  if (std::system("command -v xvfb-run >/dev/null 2>&1") != 0) GTEST_SKIP() << "no xvfb-run";
  const fs::path dir = scratch_dir("bad_input_special_editor");
  make_fifo(dir / "fifo.json");
  write_bytes(dir / "g.json", R"({"aquarelle": 1, "nodes": {}})");
  for (const std::string args :
       {"fifo.json", "g.json --script fifo.json", "g.json --script /dev/zero"}) {
    // The editor's status is printed inside xvfb-run, whose own status also counts its
    // clean-up (which fails now and then when several servers come and go).
    const CommandResult run =
        run_command("cd " + dir.string() + " && timeout -s KILL 60 xvfb-run -a sh -c '" +
                    AQ_APP_PATH + " edit " + args + " --quit --size 320x240; echo status=$?'");
    EXPECT_NE(run.output.find("status=1"), std::string::npos) << args << ": " << run.output;
    EXPECT_NE(run.output.find("only regular files"), std::string::npos)
        << args << ": " << run.output;
  }
}

}  // namespace
}  // namespace aq::test::bad_input
