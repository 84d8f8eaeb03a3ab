// `aquarelle validate` on every malformed graph in tests/data/graphs/invalid, with the real
// plugins: exit code 1 and the one expected problem, named with file, line and column, as
// listed in expected.txt (tests/core/graph_io_test.cpp checks the same files against the
// library with mirrored node types; this checks the installed types and the command agree).
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "app/cli_support.h"

namespace {

namespace fs = std::filesystem;
using aq::test::aquarelle;

const fs::path kGraphs = fs::path(AQ_SOURCE_DIR) / "tests" / "data" / "graphs";

std::string trim(const std::string& text) {
  const size_t first = text.find_first_not_of(' ');
  const size_t last = text.find_last_not_of(' ');
  return first == std::string::npos ? "" : text.substr(first, last - first + 1);
}

TEST(ValidateFiles, TheGraphTheyBreakIsValid) {
  const auto result = aquarelle("validate " + (kGraphs / "valid.json").string());
  EXPECT_EQ(result.exit_code, 0) << result.output;
}

TEST(ValidateFiles, EachMalformedGraphIsRejectedWithItsPlace) {
  std::ifstream expectations(kGraphs / "invalid" / "expected.txt");
  ASSERT_TRUE(expectations);
  std::string line;
  int checked = 0;
  while (std::getline(expectations, line)) {
    if (line.empty() || line[0] == '#') continue;
    const size_t bar1 = line.find('|');
    const size_t bar2 = line.find('|', bar1 + 1);
    ASSERT_NE(bar2, std::string::npos) << line;
    const std::string file = trim(line.substr(0, bar1));
    const std::string place = trim(line.substr(bar1 + 1, bar2 - bar1 - 1));
    const std::string expected = trim(line.substr(bar2 + 1));
    const std::string path = (kGraphs / "invalid" / file).string();

    const auto result = aquarelle("validate " + path);
    EXPECT_EQ(result.exit_code, 1) << file << "\n" << result.output;
    const std::string located = path + ":" + place + ": ";
    const size_t at = result.output.find(located);
    ASSERT_NE(at, std::string::npos) << file << ": nothing at " << place << "\n" << result.output;
    const std::string reported = result.output.substr(at, result.output.find('\n', at) - at);
    EXPECT_NE(reported.find(expected), std::string::npos)
        << file << ": expected \"" << expected << "\"\n"
        << result.output;
    EXPECT_NE(result.output.find(path + ": 1 problem(s)"), std::string::npos)
        << file << ": more than the one mistake it holds\n"
        << result.output;
    ++checked;
  }
  EXPECT_GE(checked, 40);
}

}  // namespace
