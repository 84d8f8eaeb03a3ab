// The plugin loader refuses broken plugins with a reason naming the file, and loads the rest.
#include <gtest/gtest.h>

#include <aquarelle/core/plugin_loader.h>

#include <algorithm>

namespace aq {
namespace {

std::string refusal_for(const PluginLoadReport& report, const std::string& file_part) {
  for (const auto& line : report.refused) {
    if (line.find(file_part) != std::string::npos) return line;
  }
  return "";
}

TEST(PluginLoader, RefusesBrokenPluginsAndLoadsTheRest) {
  Registry registry;
  PluginSet plugins;
  PluginLoadReport report = plugins.load({AQ_TEST_PLUGIN_DIR}, registry);

  std::string wrong_abi = refusal_for(report, "aquarelle_test_wrong_abi.so");
  EXPECT_NE(wrong_abi.find("ABI version 99"), std::string::npos) << wrong_abi;
  EXPECT_EQ(registry.find("test_wrong_abi"), nullptr);

  std::string no_entry = refusal_for(report, "aquarelle_no_entry.so");
  EXPECT_NE(no_entry.find("no entry point"), std::string::npos) << no_entry;

  std::string bad = refusal_for(report, "aquarelle_test_bad_description.so");
  EXPECT_NE(bad.find("test_bad_description"), std::string::npos) << bad;
  EXPECT_EQ(registry.find("test_bad_description"), nullptr);

  EXPECT_NE(registry.find("test_add"), nullptr) << "the good plugin still loads";
  EXPECT_EQ(report.loaded.size(), 1u);
}

TEST(PluginLoader, DuplicateTypeNamesAreRefused) {
  Registry registry;
  PluginSet plugins;
  std::string why;
  std::string file = std::string(AQ_TEST_PLUGIN_DIR) + "/aquarelle_test_nodes.so";
  ASSERT_TRUE(plugins.load_file(file, registry, &why)) << why;
  EXPECT_FALSE(plugins.load_file(file, registry, &why));
  EXPECT_NE(why.find("test_add"), std::string::npos) << why;
}

TEST(PluginLoader, BuildPluginsLoadWithoutRefusal) {
  Registry registry;
  PluginSet plugins;
  PluginLoadReport report = plugins.load({AQ_PLUGIN_BUILD_DIR}, registry);
  EXPECT_TRUE(report.refused.empty()) << report.refused.front();
  EXPECT_NE(registry.find("tint"), nullptr);
  EXPECT_NE(registry.find("vignette"), nullptr);
}

TEST(PluginLoader, PluginPathHonoursEnvironment) {
  setenv("AQUARELLE_PLUGIN_PATH", "/tmp/aq-one:/tmp/aq-two", 1);
  auto path = default_plugin_path();
  unsetenv("AQUARELLE_PLUGIN_PATH");
  ASSERT_GE(path.size(), 2u);
  EXPECT_EQ(path[0], "/tmp/aq-one");
  EXPECT_EQ(path[1], "/tmp/aq-two");
}

}  // namespace
}  // namespace aq
