// The `aquarelle` command line: help, exit codes, validation messages, rendering EXR and PNG
// under EGL and OSMesa, frame ranges, --resume and bad arguments.
#include <gtest/gtest.h>

#include <aquarelle/core/color.h>
#include <aquarelle/core/image_io.h>

#include <cmath>
#include <fstream>

#include "app/cli_support.h"
#include "support/harness.h"

namespace aq::test {
namespace {

namespace fs = std::filesystem;

void write_text(const fs::path& path, const std::string& text) {
  std::ofstream(path) << text;
}

// read -> tint -> vignette, the core issue's end-to-end graph.
fs::path write_pipeline(const fs::path& dir) {
  ImageF input = gradient_image(40, 24);
  auto written = write_image((dir / "input.exr").string(), input, WriteOptions{true, 8});
  EXPECT_TRUE(written.ok()) << written.message();
  write_text(dir / "pipeline.json", R"({
  "aquarelle": 1,
  "settings": {"width": 40, "height": 24, "frames": [1, 3], "precision": "float"},
  "nodes": {
    "src": {"type": "read", "params": {"path": "input.exr"}},
    "tint": {"type": "tint", "params": {"amount": 0.5}, "inputs": {"image": "src.image"}},
    "vig": {"type": "vignette", "inputs": {"image": "tint.image"}}
  },
  "output": "vig.image"
})");
  return dir / "pipeline.json";
}

TEST(Cli, HelpOnEveryCommand) {
  EXPECT_EQ(aquarelle("--help").exit_code, 0);
  for (const char* command : {"render", "validate", "nodes", "bench"}) {
    auto result = aquarelle(std::string(command) + " --help");
    EXPECT_EQ(result.exit_code, 0) << command << ": " << result.output;
    EXPECT_NE(result.output.find("usage: aquarelle"), std::string::npos) << command;
  }
  EXPECT_EQ(aquarelle("frobnicate").exit_code, 1);
  EXPECT_EQ(aquarelle("").exit_code, 1);
}

TEST(Cli, RenderPlanPrintsThePassesWithoutRendering) {
  auto plan = aq::test::aquarelle("render " + aq::test::source_path("graphs/underwater.json") +
                                  " --plan --quality final");
  EXPECT_EQ(plan.exit_code, 0) << plan.output;
  EXPECT_NE(plan.output.find("working size 1280x720"), std::string::npos) << plan.output;
  EXPECT_NE(plan.output.find("epilogue: blur -> vignette -> tint"), std::string::npos) << plan.output;
  auto preview = aq::test::aquarelle("render " + aq::test::source_path("graphs/underwater.json") +
                                     " --plan --quality preview");
  EXPECT_NE(preview.output.find("working size 640x360"), std::string::npos) << preview.output;
  EXPECT_NE(preview.output.find("(inside the upscale)"), std::string::npos) << preview.output;
}

TEST(Cli, NodesListsInstalledTypes) {
  auto result = aquarelle("nodes");
  ASSERT_EQ(result.exit_code, 0) << result.output;
  EXPECT_NE(result.output.find("tint"), std::string::npos);
  EXPECT_NE(result.output.find("vignette"), std::string::npos);
  EXPECT_NE(result.output.find("read"), std::string::npos);
  auto json = aquarelle("nodes tint --json");
  ASSERT_EQ(json.exit_code, 0) << json.output;
  auto parsed = nlohmann::json::parse(json.output, nullptr, false);
  ASSERT_FALSE(parsed.is_discarded()) << json.output;
  ASSERT_EQ(parsed.size(), 1u);
  EXPECT_EQ(parsed[0]["type"], "tint");
  EXPECT_EQ(aquarelle("nodes no_such_type").exit_code, 1);
}

TEST(Cli, ValidateAcceptsAGoodGraphAndRejectsBadOnesWithLocations) {
  auto dir = scratch_dir("validate");
  auto good = write_pipeline(dir);
  auto ok = aquarelle("validate " + good.string());
  EXPECT_EQ(ok.exit_code, 0) << ok.output;

  write_text(dir / "bad.json", R"({
  "aquarelle": 1,
  "nodes": {
    "src": {"type": "read", "params": {"path": "input.exr"}},
    "tint": {"type": "tint", "params": {"amount": 7}, "inputs": {"image": "src.image"}},
    "vig": {"type": "vignettte", "inputs": {"image": "tint.image"}}
  },
  "output": "vig.image"
})");
  auto bad = aquarelle("validate " + (dir / "bad.json").string());
  EXPECT_EQ(bad.exit_code, 1);
  EXPECT_NE(bad.output.find("bad.json:5:"), std::string::npos) << bad.output;
  EXPECT_NE(bad.output.find("'tint'"), std::string::npos) << bad.output;
  EXPECT_NE(bad.output.find("amount"), std::string::npos) << bad.output;
  EXPECT_NE(bad.output.find("vignettte"), std::string::npos) << bad.output;

  write_text(dir / "broken.json", "{\"aquarelle\": 1,\n  \"nodes\": {\n");
  auto broken = aquarelle("validate " + (dir / "broken.json").string());
  EXPECT_EQ(broken.exit_code, 1);
  EXPECT_NE(broken.output.find("broken.json:"), std::string::npos) << broken.output;

  EXPECT_EQ(aquarelle("validate " + (dir / "missing.json").string()).exit_code, 1);
}

class RenderBackend : public ::testing::TestWithParam<std::string> {};

TEST_P(RenderBackend, RendersExrAndPng) {
  auto dir = scratch_dir("render_" + GetParam());
  auto graph = write_pipeline(dir);
  auto exr = aquarelle("render " + graph.string() + " --frames 1 -q --gl " + GetParam() + " -o " +
                       (dir / "out.exr").string());
  ASSERT_EQ(exr.exit_code, 0) << exr.output;
  auto png = aquarelle("render " + graph.string() + " --frames 1 -q --gl " + GetParam() + " -o " +
                       (dir / "out.png").string());
  ASSERT_EQ(png.exit_code, 0) << png.output;

  auto config = ColorConfig::load();
  ASSERT_TRUE(config.ok()) << config.message();
  auto linear = read_image((dir / "out.exr").string(), *config);
  ASSERT_TRUE(linear.ok()) << linear.message();
  ASSERT_EQ(linear->width, 40);
  ASSERT_EQ(linear->height, 24);

  // Independent check of the centre pixel: tint 0.5 towards (0, 0.07, 0.1); the vignette
  // leaves the centre alone.
  ImageF input = gradient_image(40, 24);
  const float tint[3] = {0.0f, 0.07f, 0.1f};
  for (int c = 0; c < 3; ++c) {
    float expected = 0.5f * input.at(20, 12, c) + 0.5f * tint[c];
    EXPECT_NEAR(linear->at(20, 12, c), expected, 2e-3) << "channel " << c;
  }
  // PNG = sRGB encoding of the EXR (8-bit); reading it back decodes to linear again.
  auto displayed = read_image((dir / "out.png").string(), *config);
  ASSERT_TRUE(displayed.ok()) << displayed.message();
  EXPECT_LE(max_abs_diff(*displayed, *linear, 3), 0.02);
}

INSTANTIATE_TEST_SUITE_P(Backends, RenderBackend, ::testing::Values("egl", "osmesa"));

TEST(Cli, FrameRangesAndResume) {
  auto dir = scratch_dir("frames");
  auto graph = write_pipeline(dir);
  auto result = aquarelle("render " + graph.string() + " -q -o " + (dir / "f_####.exr").string());
  ASSERT_EQ(result.exit_code, 0) << result.output;
  for (int f = 1; f <= 3; ++f) {
    EXPECT_TRUE(fs::exists(dir / ("f_000" + std::to_string(f) + ".exr")));
  }
  fs::remove(dir / "f_0002.exr");
  auto time_before = fs::last_write_time(dir / "f_0001.exr");
  auto resumed =
      aquarelle("render " + graph.string() + " --resume -o " + (dir / "f_####.exr").string());
  ASSERT_EQ(resumed.exit_code, 0) << resumed.output;
  EXPECT_TRUE(fs::exists(dir / "f_0002.exr"));
  EXPECT_EQ(fs::last_write_time(dir / "f_0001.exr"), time_before) << "existing frame kept";
  EXPECT_NE(resumed.output.find("2 already there"), std::string::npos) << resumed.output;
  for (const auto& entry : fs::directory_iterator(dir)) {
    EXPECT_EQ(entry.path().string().find(".tmp"), std::string::npos)
        << "no temporary file left: " << entry.path();
  }
}

TEST(Cli, BadArgumentsAreRefusedWithExitCodeOne) {
  auto dir = scratch_dir("bad_args");
  auto graph = write_pipeline(dir).string();
  std::string out = " -o " + (dir / "x_####.exr").string();
  struct Case {
    std::string arguments;
    std::string says;
  };
  const Case cases[] = {
      {"render " + graph + out + " --frames 5-1", "first frame is after the last"},
      {"render " + graph + out + " --size 0x0", "between 1 and 16384"},
      {"render " + graph + out + " --size 99999x99999", "between 1 and 16384"},
      {"render " + graph + out + " --set nonode.amount=1", "no node 'nonode'"},
      {"render " + graph + out + " --set tint.nope=1", "no parameter 'nope'"},
      {"render " + graph + out + " --set tint.amount=5", "amount"},
      {"render " + graph + out + " --gl vulkan", "unknown GL backend"},
      {"render " + graph + out + " --gl-device gpu", "must be auto, software or the index"},
      {"bench " + graph + " --no-sweep --gl-device -1", "must be auto, software or the index"},
      {"render " + graph + " -o /nonexistent/dir/x_####.exr", "does not exist"},
      {"render " + graph + " --frames 1-3 -o " + (dir / "no_hashes.exr").string(), "####"},
      {"render " + graph, "no output"},
      {"render " + graph + out + " --precision double", "half or float"},
  };
  for (const auto& c : cases) {
    auto result = aquarelle(c.arguments);
    EXPECT_EQ(result.exit_code, 1) << c.arguments << "\n" << result.output;
    EXPECT_NE(result.output.find(c.says), std::string::npos) << c.arguments << "\n"
                                                             << result.output;
  }
}

TEST(Cli, DiskFullIsAClearError) {
  auto dir = scratch_dir("disk_full");
  auto graph = write_pipeline(dir).string();
  // /dev/full accepts opening and fails every write.
  auto result = aquarelle("render " + graph + " --frames 1 -q -o /dev/full");
  EXPECT_EQ(result.exit_code, 1) << result.output;
  EXPECT_NE(result.output.find("/dev/full"), std::string::npos) << result.output;
}

}  // namespace
}  // namespace aq::test
