// `aquarelle validate` and `render` on graphs whose object, scene and read nodes name files:
// missing, unreadable or not-a-mesh/not-an-image paths are errors naming the node, the
// parameter and the resolved path (exit 1); missing textures and material files are warnings
// saying what is used instead (exit 0); an input given several links must be a port that
// takes them; an object outside the camera's view is a warning with its bounds.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include <filesystem>
#include <fstream>
#include <string>

#include "app/cli_support.h"

namespace {

namespace fs = std::filesystem;
using aq::test::aquarelle;

void write_text(const fs::path& path, const std::string& text) {
  std::ofstream(path, std::ios::binary) << text;
}

// A graph of one object (params given) joined and rendered to its g-buffer albedo.
std::string object_graph(const nlohmann::json& object_params) {
  nlohmann::json g = {
      {"aquarelle", 1},
      {"settings", {{"width", 32}, {"height", 32}}},
      {"nodes",
       {{"thing", {{"type", "object"}, {"params", object_params}}},
        {"join", {{"type", "scene_join"}, {"inputs", {{"objects", {"thing.object"}}}}}},
        {"gbuf", {{"type", "gbuffer"}, {"inputs", {{"scene", "join.scene"}}}}}}},
      {"output", "gbuf.albedo"}};
  return g.dump(2);
}

const std::string kQuad =
    "v -1 0 1\nv 1 0 1\nv 1 0 -1\nv -1 0 -1\nvt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\n"
    "f 1/1 2/2 3/3\nf 1/1 3/3 4/4\n";

TEST(SceneFiles, MissingModelIsAnErrorWithNodeParameterAndPath) {
  const fs::path dir = aq::test::scratch_dir("scene_files_missing");
  write_text(dir / "g.json", object_graph({{"path", "models/none.obj"}}));
  const auto result = aquarelle("validate " + (dir / "g.json").string());
  EXPECT_EQ(result.exit_code, 1) << result.output;
  EXPECT_NE(result.output.find("node 'thing'"), std::string::npos) << result.output;
  EXPECT_NE(result.output.find("parameter 'path'"), std::string::npos) << result.output;
  EXPECT_NE(result.output.find((dir / "models" / "none.obj").string()), std::string::npos)
      << result.output;
  EXPECT_NE(result.output.find("does not exist"), std::string::npos) << result.output;
  const auto render =
      aquarelle("render " + (dir / "g.json").string() + " -o " + (dir / "out.exr").string());
  EXPECT_EQ(render.exit_code, 1) << render.output;
}

TEST(SceneFiles, NotAMeshAndNotAnImageAreErrors) {
  const fs::path dir = aq::test::scratch_dir("scene_files_not_a_mesh");
  write_text(dir / "notes.glb", "these are words, not a model");
  write_text(dir / "g.json", object_graph({{"path", "notes.glb"}}));
  auto result = aquarelle("validate " + (dir / "g.json").string());
  EXPECT_EQ(result.exit_code, 1) << result.output;
  EXPECT_NE(result.output.find("parameter 'path'"), std::string::npos) << result.output;
  EXPECT_NE(result.output.find((dir / "notes.glb").string()), std::string::npos) << result.output;

  write_text(dir / "picture.png", "not a picture either");
  nlohmann::json read = {
      {"aquarelle", 1},
      {"nodes", {{"r", {{"type", "read"}, {"params", {{"path", "picture.png"}}}}}}},
      {"output", "r.image"}};
  write_text(dir / "read.json", read.dump());
  result = aquarelle("validate " + (dir / "read.json").string());
  EXPECT_EQ(result.exit_code, 1) << result.output;
  EXPECT_NE(result.output.find("node 'r', parameter 'path'"), std::string::npos) << result.output;
  EXPECT_NE(result.output.find("is not an image"), std::string::npos) << result.output;
}

TEST(SceneFiles, MissingTextureAndMaterialFileAreWarnings) {
  const fs::path dir = aq::test::scratch_dir("scene_files_warnings");
  write_text(dir / "a.obj", "mtllib a.mtl\nusemtl m\n" + kQuad);
  write_text(dir / "a.mtl", "newmtl m\nKd 0.5 0.25 0.125\nmap_Kd sand.png\n");
  write_text(dir / "b.obj", "mtllib gone.mtl\nusemtl m\n" + kQuad);
  nlohmann::json g = nlohmann::json::parse(object_graph({{"path", "a.obj"}}));
  g["nodes"]["other"] = {{"type", "object"}, {"params", {{"path", "b.obj"}, {"id", 2}}}};
  g["nodes"]["join"]["inputs"]["objects"] = {"thing.object", "other.object"};
  write_text(dir / "g.json", g.dump(2));
  const auto result = aquarelle("validate " + (dir / "g.json").string());
  EXPECT_EQ(result.exit_code, 0) << result.output;
  EXPECT_NE(result.output.find("warning: "), std::string::npos) << result.output;
  EXPECT_NE(result.output.find((dir / "sand.png").string()), std::string::npos) << result.output;
  EXPECT_NE(result.output.find("using its colour (0.5, 0.25, 0.125) untextured"), std::string::npos)
      << result.output;
  EXPECT_NE(result.output.find((dir / "gone.mtl").string()), std::string::npos) << result.output;
  EXPECT_NE(result.output.find("grey 0.8"), std::string::npos) << result.output;
  // Rendering says the same and still renders.
  const auto render =
      aquarelle("render " + (dir / "g.json").string() + " -o " + (dir / "out.exr").string());
  EXPECT_EQ(render.exit_code, 0) << render.output;
  EXPECT_NE(render.output.find((dir / "sand.png").string()), std::string::npos) << render.output;
}

TEST(SceneFiles, SeveralLinksOnlyWhereThePortTakesThem) {
  const fs::path dir = aq::test::scratch_dir("scene_files_links");
  nlohmann::json g = nlohmann::json::parse(object_graph({{"source", "cube"}}));
  g["nodes"]["gbuf"]["inputs"]["scene"] = {"join.scene", "join.scene"};
  write_text(dir / "g.json", g.dump(2));
  const auto result = aquarelle("validate " + (dir / "g.json").string());
  EXPECT_EQ(result.exit_code, 1) << result.output;
  EXPECT_NE(result.output.find("takes one link, not 2"), std::string::npos) << result.output;
}

TEST(SceneFiles, ObjectOutsideTheViewIsAWarningWithItsBounds) {
  const fs::path dir = aq::test::scratch_dir("scene_files_view");
  write_text(dir / "g.json", object_graph({{"source", "cube"}, {"position", {0.0, 0.0, 40.0}}}));
  const auto render =
      aquarelle("render " + (dir / "g.json").string() + " -o " + (dir / "out.exr").string());
  EXPECT_EQ(render.exit_code, 0) << render.output;
  EXPECT_NE(render.output.find("outside the camera's view"), std::string::npos) << render.output;
  EXPECT_NE(render.output.find("(-0.5, -0.5, 39.5) to (0.5, 0.5, 40.5)"), std::string::npos)
      << render.output;
}

TEST(SceneFiles, FilesGraphIsValid) {
  const auto result =
      aquarelle("validate " + (fs::path(AQ_SOURCE_DIR) / "graphs" / "files.json").string());
  EXPECT_EQ(result.exit_code, 0) << result.output;
  EXPECT_EQ(result.output.find("warning"), std::string::npos) << result.output;
}

}  // namespace
