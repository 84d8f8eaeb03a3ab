// `final` (full size) is the default quality everywhere (issue 37): every shipped graph says
// so in its settings, and `aquarelle render` without --quality renders the flagship at full
// size. `preview` and `draft` stay explicit choices (--quality, or the editor's proxies).
#include <gtest/gtest.h>

#include <aquarelle/core/graph_io.h>

#include <filesystem>
#include <string>

#include "app/cli_support.h"
#include "support/harness.h"

namespace {

namespace fs = std::filesystem;

TEST(DefaultQuality, EveryShippedGraphDefaultsToFinal) {
  int graphs = 0;
  for (const auto& entry : fs::directory_iterator(fs::path(AQ_SOURCE_DIR) / "graphs")) {
    if (entry.path().extension() != ".json") continue;
    auto read = aq::read_graph_file(entry.path().string(), aq::test::registry());
    ASSERT_TRUE(read.ok()) << entry.path() << ": " << aq::format_problems(read.problems);
    EXPECT_EQ(read.graph.settings.quality, "final")
        << entry.path().filename() << " must default to final; preview and draft are explicit";
    ++graphs;
  }
  EXPECT_GE(graphs, 10);
}

TEST(DefaultQuality, RenderWithoutQualityWorksAtFullSize) {
  auto plan =
      aq::test::aquarelle("render " + aq::test::source_path("graphs/underwater.json") + " --plan");
  EXPECT_EQ(plan.exit_code, 0) << plan.output;
  EXPECT_NE(plan.output.find("working size 1280x720"), std::string::npos) << plan.output;
  auto files =
      aq::test::aquarelle("render " + aq::test::source_path("graphs/files.json") + " --plan");
  EXPECT_EQ(files.exit_code, 0) << files.output;
  EXPECT_EQ(files.output.find("working size 640x360"), std::string::npos) << files.output;
}

TEST(DefaultQuality, PreviewStaysAnExplicitChoice) {
  auto plan = aq::test::aquarelle("render " + aq::test::source_path("graphs/underwater.json") +
                                  " --plan --quality preview");
  EXPECT_EQ(plan.exit_code, 0) << plan.output;
  EXPECT_NE(plan.output.find("working size 640x360"), std::string::npos) << plan.output;
}

}  // namespace
