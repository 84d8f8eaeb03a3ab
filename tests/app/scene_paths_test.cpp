// Object paths and the texture paths inside model files, as a new user writes them (issue 38,
// items 1 and 2): a bare file name beside the graph keeps its textures, as `./name` does; an
// MTL's absolute `map_Kd` inside the mesh's own folder is read (resolved, then confined), one
// outside it is still refused by name.
#include <gtest/gtest.h>

#include <aquarelle/core/image_io.h>

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

void write_texture(const fs::path& path) {
  aq::ImageF image(2, 2, 4);
  for (float& v : image.pixels) v = 0.5f;
  aq::WriteOptions options;
  options.bits = 8;
  ASSERT_TRUE(aq::write_image(path.string(), image, options).ok());
}

std::string object_graph(const std::string& path) {
  nlohmann::json g = {
      {"aquarelle", 1},
      {"settings", {{"width", 32}, {"height", 32}}},
      {"nodes",
       {{"thing", {{"type", "object"}, {"params", {{"path", path}}}}},
        {"join", {{"type", "scene_join"}, {"inputs", {{"objects", {"thing.object"}}}}}},
        {"gbuf", {{"type", "gbuffer"}, {"inputs", {{"scene", "join.scene"}}}}}}},
      {"output", "gbuf.albedo"}};
  return g.dump(2);
}

const std::string kQuad =
    "mtllib coral.mtl\nusemtl m\n"
    "v -1 0 1\nv 1 0 1\nv 1 0 -1\nv -1 0 -1\nvt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\n"
    "f 1/1 2/2 3/3\nf 1/1 3/3 4/4\n";

// No warning about the texture: neither refused nor missing nor left untextured.
void expect_textured(const aq::test::CommandResult& result) {
  EXPECT_EQ(result.exit_code, 0) << result.output;
  EXPECT_EQ(result.output.find("refused"), std::string::npos) << result.output;
  EXPECT_EQ(result.output.find("untextured"), std::string::npos) << result.output;
}

TEST(ScenePaths, BareFileNameBesideTheGraphKeepsItsTextures) {
  const fs::path dir = aq::test::scratch_dir("scene_paths_bare");
  write_text(dir / "coral.obj", kQuad);
  write_text(dir / "coral.mtl", "newmtl m\nKd 1 1 1\nmap_Kd sand.png\n");
  write_texture(dir / "sand.png");
  write_text(dir / "g.json", object_graph("coral.obj"));
  write_text(dir / "dot.json", object_graph("./coral.obj"));
  const std::string in_dir = "cd '" + dir.string() + "' && " + AQ_APP_PATH;
  expect_textured(aq::test::run_command(in_dir + " validate dot.json"));
  expect_textured(aq::test::run_command(in_dir + " validate g.json"));
  expect_textured(aq::test::run_command(in_dir + " render g.json -o out.exr"));
}

TEST(ScenePaths, AbsoluteMapKdInsideTheMeshFolderIsReadOutsideIsRefused) {
  const fs::path dir = aq::test::scratch_dir("scene_paths_absolute");
  fs::create_directories(dir / "models" / "tex");
  fs::create_directories(dir / "elsewhere");
  write_texture(dir / "models" / "tex" / "sand.png");
  write_texture(dir / "elsewhere" / "sand.png");
  write_text(dir / "models" / "coral.obj", kQuad);
  // Written with a detour (models/../models) as exporters do: resolved, it is inside.
  write_text(dir / "models" / "coral.mtl",
             "newmtl m\nKd 1 1 1\nmap_Kd " +
                 (dir / "models" / ".." / "models" / "tex" / "sand.png").string() + "\n");
  write_text(dir / "g.json", object_graph("models/coral.obj"));
  expect_textured(aquarelle("validate " + (dir / "g.json").string()));
  expect_textured(
      aquarelle("render " + (dir / "g.json").string() + " -o " + (dir / "out.exr").string()));
  // The same from the model's own folder, named bare: its folder is the current one, which
  // the absolute path resolves into (this was refused as "outside the mesh's folder").
  write_text(dir / "models" / "g.json", object_graph("coral.obj"));
  const std::string in_models = "cd '" + (dir / "models").string() + "' && " + AQ_APP_PATH;
  expect_textured(aq::test::run_command(in_models + " validate g.json"));
  expect_textured(aq::test::run_command(in_models + " render g.json -o out.exr"));

  write_text(dir / "models" / "coral.mtl",
             "newmtl m\nKd 1 1 1\nmap_Kd " + (dir / "elsewhere" / "sand.png").string() + "\n");
  const auto outside = aquarelle("validate " + (dir / "g.json").string());
  EXPECT_EQ(outside.exit_code, 0) << outside.output;
  EXPECT_NE(outside.output.find("refused"), std::string::npos) << outside.output;
  EXPECT_NE(outside.output.find("outside the mesh's folder"), std::string::npos) << outside.output;
}

}  // namespace
