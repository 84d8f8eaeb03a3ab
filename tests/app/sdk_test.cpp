// `cmake --install` gives a working SDK: a plugin built outside the tree with
// find_package(Aquarelle) and aquarelle_add_plugin() loads into the installed aquarelle.
#include <gtest/gtest.h>

#include "app/cli_support.h"

namespace aq::test {
namespace {

TEST(Sdk, OutOfTreePluginBuildsAndLoads) {
  auto dir = scratch_dir("sdk");
  auto prefix = dir / "prefix";
  auto install = run_command("cmake --install " + std::string(AQ_BUILD_DIR) + " --prefix " +
                             prefix.string());
  ASSERT_EQ(install.exit_code, 0) << install.output;
  ASSERT_TRUE(std::filesystem::exists(prefix / "bin/aquarelle"));

  auto build = dir / "build";
  auto configure = run_command("cmake -S " + std::string(AQ_SOURCE_DIR) + "/tests/sdk/plugin -B " +
                               build.string() + " -DCMAKE_PREFIX_PATH=" + prefix.string());
  ASSERT_EQ(configure.exit_code, 0) << configure.output;
  auto compile = run_command("cmake --build " + build.string());
  ASSERT_EQ(compile.exit_code, 0) << compile.output;

  std::string env = "AQUARELLE_PLUGIN_PATH=" + (build / "plugins").string() + " ";
  auto nodes = run_command(env + (prefix / "bin/aquarelle").string() + " nodes sdk_invert");
  EXPECT_EQ(nodes.exit_code, 0) << nodes.output;
  EXPECT_NE(nodes.output.find("sdk_invert"), std::string::npos) << nodes.output;
  // The installed executable finds its installed plugins too.
  auto installed = run_command((prefix / "bin/aquarelle").string() + " nodes tint");
  EXPECT_EQ(installed.exit_code, 0) << installed.output;
}

}  // namespace
}  // namespace aq::test
