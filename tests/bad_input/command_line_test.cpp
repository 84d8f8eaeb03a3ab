// `aquarelle render` facing bad input and a bad environment (issue 17, items 5, 7, 10, 11 and
// 12): a mistyped GALLIUM_DRIVER (a segfault in OSMesa), an output that is the graph or an
// input file (the graph was overwritten, exit 0), a broken LUT in $OCIO (blamed on --view
// with exit 1), --set errors (attributed to the graph file), leftovers of killed renders, and
// a plugin asking for an image format that does not exist (an all-zero image, exit 0).
#include <aquarelle/core/image_io.h>
#include <fnmatch.h>
#include <sys/wait.h>
#include <unistd.h>

#include <fstream>

#include "bad_input/bad_input_support.h"

namespace aq::test::bad_input {
namespace {

bool mentions(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}

// A cube from the scene node, through the gbuffer: no input files, no test plugins.
const char* kCubeGraph = R"({
  "aquarelle": 1,
  "settings": {"width": 16, "height": 16, "frames": [1, 2], "precision": "float"},
  "nodes": {
    "model": {"type": "scene", "params": {"preset": "cube"}},
    "gbuf": {"type": "gbuffer", "inputs": {"scene": "model.scene"}},
    "tint": {"type": "tint", "params": {"amount": 0.5}, "inputs": {"image": "gbuf.albedo"}}
  },
  "output": "tint.image"
})";

// Item 5.
TEST(GlEnvironment, MistypedGalliumDriverIsExitTwoWithAMessage) {
  const fs::path dir = scratch_dir("bad_input_gallium");
  write_bytes(dir / "g.json", kCubeGraph);
  for (const std::string gl : {"auto", "osmesa"}) {
    auto result = aquarelle_within(60,
                                   "render " + (dir / "g.json").string() + " --gl " + gl +
                                       " -q -o " + (dir / "out.exr").string(),
                                   "GALLIUM_DRIVER=llvmpip");
    EXPECT_EQ(result.exit_code, 2) << gl << ": " << result.output;
    EXPECT_TRUE(mentions(result.output, "GALLIUM_DRIVER")) << gl << ": " << result.output;
  }
}

// Item 7.
TEST(OutputPaths, OutputThatIsTheGraphFileIsRefused) {
  const fs::path dir = scratch_dir("bad_input_output_graph");
  write_bytes(dir / "g.png", kCubeGraph);
  auto result = aquarelle_within(
      60, "render " + (dir / "g.png").string() + " -q -o " + (dir / "g.png").string());
  EXPECT_EQ(result.exit_code, 1) << result.output;
  EXPECT_TRUE(mentions(result.output, "is the graph file")) << result.output;
  EXPECT_EQ(file_bytes(dir / "g.png"), kCubeGraph) << "the graph was overwritten";
  // Another spelling of the same file.
  auto dotted = aquarelle_within(
      60, "render " + (dir / "g.png").string() + " -q -o " + (dir / "." / "g.png").string());
  EXPECT_EQ(dotted.exit_code, 1) << dotted.output;
  EXPECT_EQ(file_bytes(dir / "g.png"), kCubeGraph);
}

TEST(OutputPaths, OutputThatIsAnInputFileIsRefused) {
  const fs::path dir = scratch_dir("bad_input_output_input");
  ASSERT_TRUE(write_image((dir / "in.exr").string(), gradient_image(8, 8)).ok());
  const std::string before = file_bytes(dir / "in.exr");
  write_bytes(dir / "g.json", R"({"aquarelle": 1,
  "settings": {"width": 8, "height": 8, "frames": [1, 1]},
  "nodes": {"source": {"type": "read", "params": {"path": "in.exr"}},
            "tint": {"type": "tint", "inputs": {"image": "source.image"}}},
  "output": "tint.image"})");
  fs::create_symlink(dir / "in.exr", dir / "alias.exr");
  for (const std::string out : {"in.exr", "alias.exr"}) {
    auto result = aquarelle_within(
        60, "render " + (dir / "g.json").string() + " -q -o " + (dir / out).string());
    EXPECT_EQ(result.exit_code, 1) << out << ": " << result.output;
    EXPECT_TRUE(mentions(result.output, "input file")) << result.output;
  }
  EXPECT_EQ(file_bytes(dir / "in.exr"), before) << "the input was overwritten";
}

// Item 10.
TEST(Messages, BrokenLutInOcioIsExitTwoBlamingOcio) {
  const fs::path dir = scratch_dir("bad_input_ocio_lut");
  std::string config = file_bytes(source_path("ocio/config.ocio"));
  const std::string curve =
      "to_scene_reference: !<ExponentWithLinearTransform> {gamma: 2.4, offset: 0.055}";
  const size_t at = config.find(curve);
  ASSERT_NE(at, std::string::npos);
  config.replace(
      at, curve.size(),
      "from_scene_reference: !<FileTransform> {src: broken.spi1d, interpolation: linear}");
  config.replace(config.find("search_path: \"\""), 15, "search_path: \".\"");
  write_bytes(dir / "config.ocio", config);
  write_bytes(dir / "broken.spi1d", "this is not a LUT\n\x01\x02\x03");
  write_bytes(dir / "g.json", kCubeGraph);
  auto result = aquarelle_within(
      60, "render " + (dir / "g.json").string() + " -q -o " + (dir / "out.png").string(),
      "OCIO=" + (dir / "config.ocio").string());
  EXPECT_EQ(result.exit_code, 2) << result.output;
  EXPECT_TRUE(mentions(result.output, "$OCIO")) << result.output;
  EXPECT_FALSE(mentions(result.output, "--view")) << result.output;
}

TEST(Messages, SetErrorsAreTheCommandLinesNotTheGraphFiles) {
  const fs::path dir = scratch_dir("bad_input_set");
  write_bytes(dir / "g.json", kCubeGraph);
  auto result =
      aquarelle_within(60, "render " + (dir / "g.json").string() + " --set tint.amount=7 -q -o " +
                               (dir / "out.exr").string());
  EXPECT_EQ(result.exit_code, 1) << result.output;
  EXPECT_TRUE(mentions(result.output, "--set tint.amount=7")) << result.output;
  EXPECT_FALSE(mentions(result.output, "g.json:")) << result.output;
}

// Item 11.
TEST(Leftovers, TemporaryNameMatchesNoImageGlob) {
  const std::string temp = temporary_write_path("out/shot_0001.exr", 4242);
  const std::string name = fs::path(temp).filename().string();
  EXPECT_EQ(fs::path(temp).parent_path(), fs::path("out"));
  for (const char* glob : {"shot_0001*.exr", "*.exr", "shot_*", "*.exr*"}) {
    EXPECT_NE(::fnmatch(glob, name.c_str(), FNM_PERIOD), 0) << glob << " matches " << name;
  }
}

pid_t dead_pid() {
  const pid_t child = ::fork();
  if (child == 0) ::_exit(0);
  ::waitpid(child, nullptr, 0);
  return child;
}

TEST(Leftovers, ResumeRemovesStaleTemporariesAndRerendersTruncatedFrames) {
  const fs::path dir = scratch_dir("bad_input_resume");
  write_bytes(dir / "g.json", kCubeGraph);
  const std::string pattern = (dir / "f####.exr").string();
  auto first = aquarelle_within(
      60, "render " + (dir / "g.json").string() + " --frames 1-2 -q -o " + pattern);
  ASSERT_EQ(first.exit_code, 0) << first.output;
  const std::string whole = file_bytes(dir / "f0002.exr");
  write_bytes(dir / "f0002.exr", whole.substr(0, whole.size() / 2));  // cut short
  const fs::path stale = temporary_write_path((dir / "f0001.exr").string(), dead_pid());
  write_bytes(stale, "half an image");
  const fs::path alive = temporary_write_path((dir / "f0001.exr").string(), ::getpid());
  write_bytes(alive, "a running writer's");

  auto resumed = aquarelle_within(
      60, "render " + (dir / "g.json").string() + " --frames 1-2 --resume -o " + pattern);
  ASSERT_EQ(resumed.exit_code, 0) << resumed.output;
  EXPECT_TRUE(mentions(resumed.output, "1 already there")) << resumed.output;
  EXPECT_FALSE(fs::exists(stale)) << "stale temporary left";
  EXPECT_TRUE(fs::exists(alive)) << "a live writer's temporary was removed";
  EXPECT_TRUE(is_complete_image((dir / "f0002.exr").string()))
      << "the truncated frame was not rendered again";
  EXPECT_EQ(fs::file_size(dir / "f0002.exr"), whole.size());
}

// Item 12.
TEST(PluginAbi, UnknownOutputFormatIsRefusedNamingTheNode) {
  const fs::path dir = scratch_dir("bad_input_format");
  write_bytes(dir / "g.json", R"({"aquarelle": 1,
  "settings": {"width": 8, "height": 8, "frames": [1, 1]},
  "nodes": {"odd": {"type": "test_bad_format"}},
  "output": "odd.image"})");
  auto result = aquarelle_within(
      60, "render " + (dir / "g.json").string() + " -q -o " + (dir / "out.exr").string(),
      "AQUARELLE_PLUGIN_PATH=" + hostile_plugin_path());
  EXPECT_EQ(result.exit_code, 1) << result.output;
  EXPECT_TRUE(mentions(result.output, "'odd'")) << result.output;
  EXPECT_TRUE(mentions(result.output, "unknown image format 999")) << result.output;
  EXPECT_FALSE(fs::exists(dir / "out.exr"));
}

// Issue 40, class 7: what the command line echoes back (CLI11's parse errors, an unknown
// command or option) is escaped like every other message: an argument holding a newline
// cannot forge a `file:line:col:` line, nor an ESC sequence clear the terminal.
TEST(Messages, ArgumentsEchoedByTheCommandLineAreEscaped) {
  const fs::path dir = scratch_dir("bad_input_argv_escaped");
  write_bytes(dir / "g.json", kCubeGraph);
  const std::string forged = "\"$(printf 'x\\n/g.json:1:1: forged\\033[2J')\"";
  for (const std::string& arguments :
       {"render " + (dir / "g.json").string() + " --quiet=" + forged,  // CLI11's ParseError
        "render " + (dir / "g.json").string() + " --" + forged,        // unknown option
        std::string("rend") + forged,                                  // unknown command
        "nodes " + forged,                                             // unknown node type
        "validate " + (dir / "g.json").string() + " " + forged,        // a second graph
        "render " + (dir / "g.json").string() + " " + forged,          // a second graph
        "bench --warmup " + forged}) {                                 // a bad number
    auto result = aquarelle_within(30, arguments);
    EXPECT_EQ(result.exit_code, 1) << arguments << ": " << result.output;
    const std::string first = result.output.substr(0, result.output.find('\n'));
    EXPECT_TRUE(mentions(first, "\\n/g.json:1:1: forged\\x1b[2J")) << result.output;
    EXPECT_FALSE(mentions(result.output, "\x1b")) << arguments;
    EXPECT_FALSE(mentions(result.output, "\n/g.json:1:1")) << arguments;
  }
}

}  // namespace
}  // namespace aq::test::bad_input
