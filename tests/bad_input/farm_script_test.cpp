// Round three (issue 40), class 2: scripts/slurm-render.sh writes job scripts that run nothing
// but `aquarelle render` whatever the file names hold, and reads frame numbers as decimal
// (bash arithmetic read 0240 as octal 160: frames 161-240 were never rendered and the check job
// called the range complete). sbatch and aquarelle are stand-ins that record their arguments;
// the generated render script runs for every array task and the check script once. A property
// test feeds it random hostile names (newlines, $(...), backquotes, quotes, ESC, globs).
#include <random>

#include "bad_input/bad_input_support.h"

namespace aq::test::bad_input {
namespace {

std::string shell_quote(const std::string& text) {
  std::string out = "'";
  for (char c : text) out += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return out + "'";
}

// A folder with fake `sbatch` (keeps the script, prints a job id) and `aquarelle` (appends its
// arguments, one per line, NUL-separated per call, to calls.txt).
fs::path fake_farm(const std::string& name) {
  const fs::path dir = scratch_dir(name);
  fs::create_directories(dir / "bin");
  write_bytes(dir / "bin" / "sbatch",
              "#!/usr/bin/env bash\nfor a in \"$@\"; do last=\"$a\"; done\n"
              "n=$(ls \"$FARM\"/job-* 2>/dev/null | wc -l)\ncp \"$last\" \"$FARM/job-$n\"\n"
              "echo $((1000 + n))\n");
  write_bytes(dir / "bin" / "aquarelle",
              "#!/usr/bin/env bash\nfor a in \"$@\"; do printf '%s\\n' \"$a\"; done "
              ">>\"$FARM/calls.txt\"\nprintf '\\0\\n' >>\"$FARM/calls.txt\"\n");
  write_bytes(dir / "bin" / "iinfo", "#!/usr/bin/env bash\nexit 0\n");
  fs::permissions(dir / "bin" / "sbatch", fs::perms::owner_all, fs::perm_options::add);
  fs::permissions(dir / "bin" / "aquarelle", fs::perms::owner_all, fs::perm_options::add);
  fs::permissions(dir / "bin" / "iinfo", fs::perms::owner_all, fs::perm_options::add);
  return dir;
}

struct Submission {
  CommandResult submit;
  std::string calls;  // what the fake aquarelle was called with, every task run
  CommandResult check;
};

// Submits GRAPH (a file made in the farm folder) with OUT and ARGS, runs every array task and
// the check job.
Submission submit(const fs::path& farm, const std::string& graph_name, const std::string& args,
                  int tasks) {
  write_bytes(farm / graph_name, "{}");
  const std::string env =
      "cd " + shell_quote(farm.string()) + " && FARM=" + shell_quote(farm.string()) +
      " PATH=" + shell_quote((farm / "bin").string()) +
      ":$PATH AQUARELLE=" + shell_quote((farm / "bin" / "aquarelle").string()) + " ";
  Submission s;
  s.submit =
      run_command(env + "timeout 30 bash " + shell_quote(source_path("scripts/slurm-render.sh")) +
                  " " + shell_quote(graph_name) + " out/####.exr " + args + " 2>&1");
  for (int task = 0; task < tasks; ++task) {
    run_command(env + "SLURM_ARRAY_TASK_ID=" + std::to_string(task) + " timeout 10 bash job-0");
  }
  s.calls = file_bytes(farm / "calls.txt");
  s.check = run_command(env + "timeout 30 bash job-1 2>&1");
  return s;
}

TEST(Farm, FramesWithLeadingZerosAreDecimal) {
  const fs::path farm = fake_farm("bad_input_farm_octal");
  Submission s = submit(farm, "g.json", "--frames 0001-0240 --chunk 0080", 3);
  ASSERT_EQ(s.submit.exit_code, 0) << s.submit.output;
  EXPECT_NE(s.submit.output.find("frames 1-240"), std::string::npos) << s.submit.output;
  EXPECT_NE(s.calls.find("161-240"), std::string::npos) << s.calls;
  // No frame file exists: the check job must list all 240 as missing.
  EXPECT_EQ(s.check.exit_code, 1) << s.check.output;
  EXPECT_NE(s.check.output.find("240 of 240"), std::string::npos) << s.check.output;
}

TEST(Farm, AGraphNameWithANewlineRunsNothingElse) {
  const fs::path farm = fake_farm("bad_input_farm_newline");
  const std::string name = "g\ntouch pwned\n.json";
  Submission s = submit(farm, name, "--frames 1-2 --chunk 1", 2);
  ASSERT_EQ(s.submit.exit_code, 0) << s.submit.output;
  EXPECT_FALSE(fs::exists(farm / "pwned")) << "the job script ran a line of the file name";
  EXPECT_NE(s.calls.find("/" + name + "\n"), std::string::npos) << s.calls;
}

// Random names: whatever they hold, the tasks call aquarelle with exactly that file and nothing
// else runs (a canary command in the name would create its file).
TEST(FarmProperty, RandomHostileNamesReachAquarelleIntact) {
  const std::vector<std::string> parts = {"\n",
                                          "$(touch canary)",
                                          "`touch canary`",
                                          "'",
                                          "\"",
                                          "\\",
                                          ";touch canary;",
                                          "\x1b[2J",
                                          " ",
                                          "*",
                                          "$HOME",
                                          "#",
                                          "\t",
                                          "a",
                                          "%"};
  std::mt19937 random(40);
  for (int round = 0; round < 8; ++round) {
    const fs::path farm = fake_farm("bad_input_farm_property_" + std::to_string(round));
    std::string name = "g";
    for (int i = 0; i < 5; ++i) name += parts[random() % parts.size()];
    name += ".json";
    Submission s = submit(farm, name, "--frames 1-1 --chunk 1 -- --set " + shell_quote(name), 1);
    ASSERT_EQ(s.submit.exit_code, 0) << s.submit.output;
    EXPECT_FALSE(fs::exists(farm / "canary")) << "round " << round;
    EXPECT_NE(s.calls.find("/" + name + "\n-o\n"), std::string::npos) << "round " << round << ":\n"
                                                                      << s.calls;
    EXPECT_NE(s.calls.find("--set\n" + name + "\n"), std::string::npos) << s.calls;
    EXPECT_EQ(s.submit.output.find('\x1b'), std::string::npos) << "raw ESC in the messages";
  }
}

}  // namespace
}  // namespace aq::test::bad_input
