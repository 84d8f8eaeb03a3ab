// The editor window under Xvfb for tests: a fresh folder per test, and `aquarelle edit` run
// in scripted mode inside xvfb-run (skipped where xvfb-run is not installed).
#pragma once

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include <unistd.h>

namespace aq::test {

namespace fs = std::filesystem;

inline bool have_xvfb() {
  return std::system("command -v xvfb-run >/dev/null 2>&1") == 0;
}

inline nlohmann::json read_json(const fs::path& path) {
  std::ifstream in(path);
  return nlohmann::json::parse(in);
}

class EditorWindowTest : public ::testing::Test {
 protected:
  void SetUp() override {
    if (!have_xvfb()) GTEST_SKIP() << "xvfb-run is not installed (apt-get install xvfb)";
    dir_ = fs::temp_directory_path() /
           ("aq_editor_window_test_" + std::to_string(::getpid()) + "_" +
            ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override {
    if (!dir_.empty() && !HasFailure()) fs::remove_all(dir_);
  }

  // Writes `script` and runs it on graph.json at 1280x720 with a screenshot; returns the status.
  int run_script(const nlohmann::json& script, std::string* log) {
    std::ofstream(dir_ / "script.json") << script.dump(2);
    return run_editor(
        "graph.json --script script.json --screenshot shot.png --quit --size 1280x720", log);
  }

  // Runs `aquarelle edit` under xvfb-run; returns the editor's exit status, its output in `log`.
  // The status is written by a shell inside xvfb-run: xvfb-run's own status also reflects its
  // clean-up, which can fail when several Xvfb servers come and go at once.
  int run_editor(const std::string& args, std::string* log) {
    const fs::path log_path = dir_ / "editor.log";
    const fs::path status_path = dir_ / "editor.status";
    fs::remove(status_path);
    for (int attempt = 0; attempt < 3 && !fs::exists(status_path); ++attempt) {
      std::string inner = "'" + std::string(AQ_APP_PATH) + "' edit " + args + "; echo \\$? > '" +
                          status_path.string() + "'";
      std::string command = "cd '" + dir_.string() +
                            "' && xvfb-run -a -s '-screen 0 1600x1200x24' sh -c \"" + inner +
                            "\" > '" + log_path.string() + "' 2>&1";
      (void)std::system(command.c_str());  // no status file: Xvfb did not start; try again
    }
    std::ifstream in(log_path);
    std::stringstream text;
    text << in.rdbuf();
    *log = text.str();
    std::ifstream status_file(status_path);
    int status = -1;
    status_file >> status;
    return status;
  }

  fs::path dir_;
};

}  // namespace aq::test
