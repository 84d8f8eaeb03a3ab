// `aquarelle render` and the editor's presentation data: a bypassed node ("bypass": true on the
// node) renders as if it were removed, in `render` as in the editor; a bypassed node with
// nothing to pass through is refused by name; node groups (editor.groups) change no pixel; old
// graphs that kept bypass in the editor section still render bypassed.
#include <gtest/gtest.h>

#include <aquarelle/core/color.h>
#include <aquarelle/core/image_io.h>

#include <fstream>

#include "app/cli_support.h"
#include "support/harness.h"

namespace aq::test {
namespace {

namespace fs = std::filesystem;

void write_text(const fs::path& path, const std::string& text) {
  std::ofstream(path) << text;
}

// read → tint → vignette; `tint_extra` goes into the tint node, `editor` is the editor section.
std::string pipeline(const std::string& tint_extra, const std::string& editor = "") {
  return R"({
  "aquarelle": 1,
  "settings": {"width": 40, "height": 24, "frames": [1, 1], "precision": "float"},
  "nodes": {
    "src": {"type": "read", "params": {"path": "input.exr"}},
    "tint": {"type": "tint", "params": {"amount": 0.5}, "inputs": {"image": "src.image"})" +
         tint_extra + R"(},
    "vig": {"type": "vignette", "params": {"strength": 0.8}, "inputs": {"image": "tint.image"}}
  },
  "output": "vig.image")" +
         (editor.empty() ? "" : ",\n  \"editor\": " + editor) + "\n}\n";
}

// The same without the tint: the vignette reads the source.
const char* kWithoutTint = R"({
  "aquarelle": 1,
  "settings": {"width": 40, "height": 24, "frames": [1, 1], "precision": "float"},
  "nodes": {
    "src": {"type": "read", "params": {"path": "input.exr"}},
    "vig": {"type": "vignette", "params": {"strength": 0.8}, "inputs": {"image": "src.image"}}
  },
  "output": "vig.image"
}
)";

class RenderPresentation : public ::testing::Test {
 protected:
  void SetUp() override {
    dir = scratch_dir("bypass_render");
    auto written =
        write_image((dir / "input.exr").string(), gradient_image(40, 24), WriteOptions{true, 8});
    ASSERT_TRUE(written.ok()) << written.message();
  }
  // Renders the graph text to an EXR and reads it back.
  ImageF render(const std::string& name, const std::string& text) {
    write_text(dir / (name + ".json"), text);
    auto result = aquarelle("render " + (dir / (name + ".json")).string() + " -q -o " +
                            (dir / (name + ".exr")).string());
    EXPECT_EQ(result.exit_code, 0) << name << ": " << result.output;
    auto config = ColorConfig::load();
    EXPECT_TRUE(config.ok());
    auto image = read_image((dir / (name + ".exr")).string(), *config);
    EXPECT_TRUE(image.ok()) << name << ": " << image.message();
    return image.ok() ? *image : ImageF{};
  }
  fs::path dir;
};

TEST_F(RenderPresentation, ABypassedNodeRendersAsIfRemoved) {
  const ImageF without = render("without", kWithoutTint);
  const ImageF with_tint = render("with", pipeline(""));
  const ImageF bypassed = render("bypassed", pipeline(R"(, "bypass": true)"));
  ASSERT_EQ(bypassed.width, 40);
  ASSERT_EQ(bypassed.height, 24);
  EXPECT_GT(max_abs_diff(with_tint, without), 0.05) << "the tint changes the picture";
  EXPECT_EQ(max_abs_diff(bypassed, without), 0.0) << "bypass passes the input through";
  // "bypass": false is the node as usual.
  EXPECT_EQ(max_abs_diff(render("enabled", pipeline(R"(, "bypass": false)")), with_tint), 0.0);
}

TEST_F(RenderPresentation, OldGraphsWithBypassInTheEditorSectionStillRenderBypassed) {
  const ImageF without = render("without", kWithoutTint);
  const ImageF migrated = render("old", pipeline("", R"({"bypassed": {"tint": true}})"));
  EXPECT_EQ(max_abs_diff(migrated, without), 0.0);
}

TEST_F(RenderPresentation, ABypassedSourceIsRefusedByName) {
  const std::string text = R"({
  "aquarelle": 1,
  "settings": {"width": 40, "height": 24},
  "nodes": {
    "src": {"type": "read", "bypass": true, "params": {"path": "input.exr"}},
    "vig": {"type": "vignette", "inputs": {"image": "src.image"}}
  },
  "output": "vig.image"
}
)";
  write_text(dir / "source.json", text);
  auto result = aquarelle("render " + (dir / "source.json").string() + " -q -o " +
                          (dir / "source.exr").string());
  EXPECT_NE(result.exit_code, 0);
  EXPECT_NE(result.output.find("node 'src' (read) is bypassed"), std::string::npos)
      << result.output;
  EXPECT_NE(result.output.find("enable it"), std::string::npos) << result.output;
  // `validate` says so too, at the node.
  auto validated = aquarelle("validate " + (dir / "source.json").string());
  EXPECT_NE(validated.exit_code, 0);
  EXPECT_NE(validated.output.find("is bypassed"), std::string::npos) << validated.output;
}

TEST_F(RenderPresentation, NodeGroupsChangeNoPixel) {
  const ImageF plain = render("plain", pipeline(""));
  const ImageF grouped = render(
      "grouped", pipeline("", R"({"positions": {"src": [0, 0], "tint": [250, 0], "vig": [500, 0]},
    "groups": [{"name": "look", "nodes": ["tint", "vig"], "collapsed": true, "position": [250, 0]}]})"));
  ASSERT_EQ(grouped.width, 40);
  EXPECT_EQ(max_abs_diff(grouped, plain), 0.0);
}

}  // namespace
}  // namespace aq::test
