// Issue 39 in the real window under Xvfb (scripted mode), plus the editor without a display:
// autosave recovery after a kill, quick gestures, failed plugin loads shown in the editor.

// Issue 39: the editor autosaves shortly after each completed edit, so a kill one second after
// an edit loses nothing: the real window under Xvfb makes an edit in scripted mode and keeps
// running; the test kills it (SIGKILL) one second after the edit, then a second editor run
// recovers the autosave (the recovery prompt's action) and saves: the edit is there.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include <chrono>
#include <csignal>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <thread>

#include "support/harness.h"
#include "window_fixture.h"

namespace {

namespace fs = std::filesystem;
using aq::test::EditorWindowTest;
using aq::test::read_json;

std::string read_text(const fs::path& path) {
  std::ifstream in(path);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

TEST_F(EditorWindowTest, KillOneSecondAfterAnEditThenRestartRecoversIt) {
  fs::copy_file(aq::test::source_path("graphs/tint.json"), dir_ / "graph.json");
  // The edit, then the editor idles (a long wait) until it is killed.
  std::ofstream(dir_ / "edit.json") << R"([
    {"do": "set_param", "node": "tint", "param": "amount", "value": 0.25},
    {"do": "wait", "frames": 1000000}
  ])";
  const fs::path log = dir_ / "first.log";
  const fs::path pid_file = dir_ / "editor.pid";
  const std::string inner = "'" + std::string(AQ_APP_PATH) +
                            "' edit graph.json --script edit.json --size 640x400 & echo \\$! > '" +
                            pid_file.string() + "'; wait";
  const std::string command = "cd '" + dir_.string() +
                              "' && xvfb-run -a -s '-screen 0 1024x768x24' sh -c \"" + inner +
                              "\" > '" + log.string() + "' 2>&1 &";
  ASSERT_EQ(std::system(command.c_str()), 0);
  // The edit is made once the script starts; the log says so.
  const auto start = std::chrono::steady_clock::now();
  while (read_text(log).find("(set_param): ") == std::string::npos) {
    ASSERT_LT(std::chrono::steady_clock::now() - start, std::chrono::seconds(120))
        << "the editor never made the edit:\n"
        << read_text(log);
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  std::this_thread::sleep_for(std::chrono::seconds(1));
  int pid = 0;
  std::ifstream(pid_file) >> pid;
  ASSERT_GT(pid, 0);
  ::kill(pid, SIGKILL);  // no clean-up: what a crash or a power cut leaves
  for (int i = 0; i < 500 && ::kill(pid, 0) == 0; ++i) {
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  ASSERT_TRUE(fs::exists(dir_ / "graph.json.autosave.json") ||
              fs::exists(dir_ / "graph.autosave.json"))
      << "no autosave one second after the edit:\n"
      << read_text(log);
  EXPECT_EQ(read_json(dir_ / "graph.json"), read_json(aq::test::source_path("graphs/tint.json")))
      << "the graph itself is untouched until the user saves";

  std::ofstream(dir_ / "recover.json") << R"([{"do": "recover"}, {"do": "save"}])";
  std::string second;
  ASSERT_EQ(run_editor("graph.json --script recover.json --quit --size 640x400", &second), 0)
      << second;
  const nlohmann::json saved = read_json(dir_ / "graph.json");
  EXPECT_DOUBLE_EQ(saved["nodes"]["tint"]["params"]["amount"].get<double>(), 0.25) << saved.dump(2);
}

}  // namespace

// Issue 39: mouse gestures a UI frame is too slow to see as they happened, in the real window
// under Xvfb: a press-and-drag from an output port that has left the port before the next frame
// starts a link (it moved the node), and a double-click on a link whose two clicks are 0.15 s
// apart but 30 UI frames apart adds a reroute dot (ImGui, timing clicks by its frames, missed
// most of them).
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include <filesystem>
#include <fstream>
#include <string>

#include "support/harness.h"
#include "window_fixture.h"

namespace {

namespace fs = std::filesystem;
using aq::test::EditorWindowTest;
using aq::test::read_json;

TEST_F(EditorWindowTest, QuickDragFromAPortLinksAndADoubleClickOnALinkAddsADot) {
  fs::copy_file(aq::test::source_path("graphs/tint.json"), dir_ / "graph.json");
  nlohmann::json script = {
      {{"do", "add_node"}, {"type", "blur"}, {"id", "soft"}, {"at", {300, 420}}},
      {{"do", "fit"}},
      {{"do", "save"}, {"path", "before.json"}},
      {{"do", "drag_link"}, {"from", "tint.image"}, {"to", "soft.image"}, {"quick", true}},
      {{"do", "double_click_link"}, {"from", "light.image"}, {"to", "tint.image"}},
      {{"do", "save"}, {"path", "after.json"}},
  };
  std::string log;
  ASSERT_EQ(run_script(script, &log), 0) << log;
  const nlohmann::json before = read_json(dir_ / "before.json");
  const nlohmann::json after = read_json(dir_ / "after.json");
  EXPECT_EQ(after["nodes"]["soft"]["inputs"]["image"], "tint.image") << after.dump(2);
  EXPECT_EQ(after["editor"]["positions"]["tint"], before["editor"]["positions"]["tint"])
      << "the quick drag must not move the node";
  ASSERT_TRUE(after["editor"].contains("reroutes")) << after.dump(2) << log;
  EXPECT_FALSE(after["editor"]["reroutes"].empty());
  EXPECT_NE(after["editor"]["reroutes"].dump().find("tint"), std::string::npos)
      << after["editor"]["reroutes"].dump();
}

}  // namespace

// Issue 39: plugins that failed to load are reported in the editor (the status line and a
// "Plugins (failed)" menu), not only on the terminal. The real window under Xvfb with a plugin
// folder holding a file that is not a plugin.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>

#include "support/harness.h"
#include "window_fixture.h"

namespace {

namespace fs = std::filesystem;
using aq::test::EditorWindowTest;

TEST_F(EditorWindowTest, AFailedPluginLoadIsShownInTheEditor) {
  fs::create_directories(dir_ / "plugins");
  std::ofstream(dir_ / "plugins" / "aquarelle_broken.so") << "not a shared library\n";
  ::setenv("AQUARELLE_PLUGIN_PATH", (dir_ / "plugins").c_str(), 1);
  std::ofstream(dir_ / "script.json")
      << R"([{"do": "expect_status", "contains": "aquarelle_broken.so"},
             {"do": "expect_status", "contains": "failed to load"}])";
  std::string log;
  const int status = run_editor("new.json --script script.json --quit --size 640x400", &log);
  ::unsetenv("AQUARELLE_PLUGIN_PATH");
  EXPECT_EQ(status, 0) << log;
}

}  // namespace

// Issue 40: `aquarelle edit` without a display is a problem of the environment, not of the
// user's input: exit status 2 (as every command uses it) and one line that says what to do.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include <sys/wait.h>
#include <unistd.h>

#include "support/harness.h"

namespace {

namespace fs = std::filesystem;

TEST(EditorWithoutDisplay, ExitsTwoWithOneLine) {
  const fs::path dir = fs::temp_directory_path() / ("aq_no_display_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  const fs::path log = dir / "log.txt";
  const std::string command = "cd '" + dir.string() + "' && env -u DISPLAY -u WAYLAND_DISPLAY '" +
                              AQ_APP_PATH + "' edit graph.json > '" + log.string() + "' 2>&1";
  const int raw = std::system(command.c_str());
  ASSERT_TRUE(WIFEXITED(raw));
  std::ifstream in(log);
  std::stringstream text;
  text << in.rdbuf();
  const std::string output = text.str();
  EXPECT_EQ(WEXITSTATUS(raw), 2) << output;
  EXPECT_EQ(std::count(output.begin(), output.end(), '\n'), 1) << output;
  EXPECT_NE(output.find("xvfb-run"), std::string::npos) << output;
  EXPECT_FALSE(fs::exists(dir / "graph.json")) << "nothing written";
  fs::remove_all(dir);
}

}  // namespace
