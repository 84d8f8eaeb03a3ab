// The command line on CLI11 (app/cli.h, issue 41): one help style on every command, --version,
// --opt=value, typo suggestions for commands and options, and the exit codes the README
// documents (0 ok, 1 bad input, 2 environment; 130 is robustness_test's).
#include <gtest/gtest.h>

#include <cctype>
#include <string>

#include "app/cli_support.h"
#include "support/harness.h"

namespace aq::test {
namespace {

bool says(const CommandResult& result, const std::string& part) {
  return result.output.find(part) != std::string::npos;
}

TEST(CommandLine, EveryCommandHasHelpInTheSameStyle) {
  for (const char* command : {"render", "validate", "nodes", "bench", "edit"}) {
    for (const char* flag : {"--help"}) {
      auto result = aquarelle(std::string(command) + " " + flag);
      EXPECT_EQ(result.exit_code, 0) << command << " " << flag << ": " << result.output;
      EXPECT_EQ(result.output.rfind(std::string("usage: aquarelle ") + command, 0), 0u)
          << "the usage line comes first: " << result.output;
      EXPECT_TRUE(says(result, "\nOptions:\n  -h,--help")) << result.output;
      EXPECT_TRUE(says(result, "Exit codes: 0 ")) << result.output;
    }
  }
  EXPECT_EQ(aquarelle("validate -h").output, aquarelle("validate --help").output);
  auto top = aquarelle("--help");
  EXPECT_EQ(top.exit_code, 0);
  EXPECT_EQ(aquarelle("help").output, top.output);
  EXPECT_EQ(top.output.rfind("usage: aquarelle <command>", 0), 0u) << top.output;
  for (const char* command : {"render", "validate", "nodes", "bench", "edit"})
    EXPECT_TRUE(says(top, std::string("\n  ") + command + " ")) << top.output;
}

TEST(CommandLine, VersionPrintsTheVersion) {
  auto result = aquarelle("--version");
  EXPECT_EQ(result.exit_code, 0) << result.output;
  EXPECT_EQ(result.output.rfind("aquarelle ", 0), 0u) << result.output;
  EXPECT_TRUE(result.output.size() > 10 && std::isdigit(result.output[10])) << result.output;
}

TEST(CommandLine, OptionsTakeTheirValueAfterAnEqualsSign) {
  const std::string graph = source_path("graphs/underwater.json");
  auto spaced = aquarelle("render " + graph + " --plan --quality preview");
  auto equals = aquarelle("render " + graph + " --plan --quality=preview");
  ASSERT_EQ(equals.exit_code, 0) << equals.output;
  EXPECT_TRUE(says(equals, "working size 640x360")) << equals.output;
  EXPECT_EQ(equals.output, spaced.output);
}

TEST(CommandLine, ATypoGetsASuggestionAndExitCodeOne) {
  auto command = aquarelle("rendr graph.json");
  EXPECT_EQ(command.exit_code, 1);
  EXPECT_TRUE(says(command, "unknown command 'rendr' (did you mean 'render'?)")) << command.output;
  const std::string graph = source_path("graphs/tint.json");
  auto option = aquarelle("render " + graph + " --frmes 1-3 -o out.exr");
  EXPECT_EQ(option.exit_code, 1);
  EXPECT_TRUE(says(option, "aquarelle render: unknown option '--frmes' (did you mean '--frames'?"))
      << option.output;
  auto spelled = aquarelle("bench " + graph + " --no-swep");
  EXPECT_EQ(spelled.exit_code, 1);
  EXPECT_TRUE(says(spelled, "did you mean '--no-sweep'?")) << spelled.output;
  auto far = aquarelle("validate " + graph + " --frobnicate");
  EXPECT_EQ(far.exit_code, 1);
  EXPECT_TRUE(says(far, "unknown option '--frobnicate' (see --help)")) << far.output;
}

TEST(CommandLine, AMissingValueIsExitCodeOne) {
  auto result = aquarelle("render " + source_path("graphs/tint.json") + " -o out.exr --size");
  EXPECT_EQ(result.exit_code, 1) << result.output;
  EXPECT_TRUE(says(result, "aquarelle render: --size needs a value")) << result.output;
}

TEST(CommandLine, TheEnvironmentIsExitCodeTwo) {
  auto scratch = scratch_dir("command_line_environment");
  auto result = aquarelle("render " + source_path("graphs/tint.json") + " -q --gl-device 99 -o " +
                          (scratch / "out.exr").string());
  EXPECT_EQ(result.exit_code, 2) << result.output;
  EXPECT_TRUE(says(result, "GL device '99' is not auto, software or the index")) << result.output;
}

TEST(CommandLine, RepeatedOptionsEachTakeOneValue) {
  // --set twice, then the graph: neither --set swallows the graph as a second value.
  auto scratch = scratch_dir("command_line_repeated");
  auto result = aquarelle("render --set tint.amount=0.25 --set tint.amount=0.5 " +
                          source_path("graphs/tint.json") + " -q --size 16x16 -o " +
                          (scratch / "out.exr").string());
  EXPECT_EQ(result.exit_code, 0) << result.output;
  auto bad = aquarelle("render --set tint.amount=7 " + source_path("graphs/tint.json") + " -q -o " +
                       (scratch / "bad.exr").string());
  EXPECT_EQ(bad.exit_code, 1);
  EXPECT_TRUE(says(bad, "--set tint.amount=7")) << bad.output;
}

}  // namespace
}  // namespace aq::test
