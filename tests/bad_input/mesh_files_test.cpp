// Hostile mesh files (issue 17, items 1, 2, 4 and 6), loaded through the scene node: a glTF
// hierarchy 20,000 deep (crashed Assimp), tiny PLY and GLB files declaring gigabytes, files
// referring outside their folder (an error must name, never print, them), and one polygon of
// 200,000 vertices (quadratic ear clipping: over a minute).
#include <cmath>
#include <cstring>
#include <vector>

#include "bad_input/bad_input_support.h"

namespace aq::test::bad_input {
namespace {

bool mentions(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}

// Item 1.
TEST(MeshHierarchy, TwentyThousandDeepGltfIsRefusedByName) {
  const fs::path dir = scratch_dir("bad_input_deep_gltf");
  write_bytes(dir / "deep.gltf", gltf_chain(20000, data_uri(triangle_bytes())));
  auto image = load_mesh(dir / "deep.gltf");
  ASSERT_FALSE(image.ok());
  EXPECT_TRUE(mentions(image.message(), "deep.gltf")) << image.message();
  EXPECT_TRUE(mentions(image.message(), "levels deep")) << image.message();
  EXPECT_TRUE(mentions(image.message(), "'model'")) << image.message();
}

TEST(MeshHierarchy, ShallowChainStillLoadsAndDraws) {
  const fs::path dir = scratch_dir("bad_input_shallow_gltf");
  write_bytes(dir / "chain.gltf", gltf_chain(20, data_uri(triangle_bytes())));
  auto image = load_mesh(dir / "chain.gltf");
  ASSERT_TRUE(image.ok()) << image.message();
  EXPECT_GT(covered(*image), 0.05);
}

TEST(MeshHierarchy, CycleInNodeChildrenIsRefused) {
  const fs::path dir = scratch_dir("bad_input_cycle_gltf");
  auto gltf = nlohmann::json::parse(gltf_chain(3, data_uri(triangle_bytes())));
  gltf["nodes"][2]["children"] = {0};
  write_bytes(dir / "cycle.gltf", gltf.dump());
  auto image = load_mesh(dir / "cycle.gltf");
  ASSERT_FALSE(image.ok());
  EXPECT_TRUE(mentions(image.message(), "cycle.gltf")) << image.message();
}

TEST(MeshFormats, OnlyTheDocumentedFormatsAreRead) {
  const fs::path dir = scratch_dir("bad_input_mesh_format");
  write_bytes(dir / "tri.dae", "<?xml version=\"1.0\"?><COLLADA></COLLADA>");
  auto image = load_mesh(dir / "tri.dae");
  ASSERT_FALSE(image.ok());
  EXPECT_TRUE(mentions(image.message(), "'.dae' files are not read")) << image.message();
}

// Item 2.
TEST(MeshDeclaredSizes, TinyPlyDeclaringTwoBillionVerticesIsRefused) {
  const fs::path dir = scratch_dir("bad_input_ply_huge");
  write_bytes(dir / "huge.ply",
              "ply\nformat ascii 1.0\nelement vertex 2000000000\nproperty float x\n"
              "property float y\nproperty float z\nelement face 1\n"
              "property list uchar int vertex_indices\nend_header\n0 0 0\n1 0 0\n0 1 0\n"
              "3 0 1 2\n");
  auto image = load_mesh(dir / "huge.ply");
  ASSERT_FALSE(image.ok());
  EXPECT_TRUE(mentions(image.message(), "huge.ply")) << image.message();
  EXPECT_TRUE(mentions(image.message(), "2000000000 vertex")) << image.message();
}

TEST(MeshDeclaredSizes, BinaryPlyWithHonestHeaderLoads) {
  const fs::path dir = scratch_dir("bad_input_ply_ok");
  std::string ply =
      "ply\nformat binary_little_endian 1.0\nelement vertex 3\nproperty float x\n"
      "property float y\nproperty float z\nelement face 1\n"
      "property list uchar int vertex_indices\nend_header\n";
  ply += triangle_bytes();
  const unsigned char count = 3;
  const int indices[3] = {0, 1, 2};
  ply += std::string(reinterpret_cast<const char*>(&count), 1);
  ply += std::string(reinterpret_cast<const char*>(indices), sizeof(indices));
  write_bytes(dir / "tri.ply", ply);
  auto image = load_mesh(dir / "tri.ply");
  ASSERT_TRUE(image.ok()) << image.message();
  EXPECT_GT(covered(*image), 0.05);
}

std::string glb(const std::string& json, uint32_t bin_declared, const std::string& bin) {
  std::string padded = json;
  while (padded.size() % 4 != 0) padded += ' ';
  auto u32 = [](uint32_t v) { return std::string(reinterpret_cast<const char*>(&v), 4); };
  std::string body = u32(static_cast<uint32_t>(padded.size())) + "JSON" + padded +
                     u32(bin_declared) + std::string("BIN\0", 4) + bin;
  return "glTF" + u32(2) + u32(static_cast<uint32_t>(12 + body.size())) + body;
}

TEST(MeshDeclaredSizes, GlbChunkOfTwoGigabytesIsRefused) {
  const fs::path dir = scratch_dir("bad_input_glb_huge");
  auto gltf = nlohmann::json::parse(gltf_chain(1, ""));
  gltf["buffers"][0].erase("uri");
  write_bytes(dir / "huge.glb", glb(gltf.dump(), 2000000000u, triangle_bytes()));
  ASSERT_LT(fs::file_size(dir / "huge.glb"), 1024u);
  auto image = load_mesh(dir / "huge.glb");
  ASSERT_FALSE(image.ok());
  EXPECT_TRUE(mentions(image.message(), "huge.glb")) << image.message();
  EXPECT_TRUE(mentions(image.message(), "2000000000")) << image.message();
}

TEST(MeshDeclaredSizes, HonestGlbLoads) {
  const fs::path dir = scratch_dir("bad_input_glb_ok");
  auto gltf = nlohmann::json::parse(gltf_chain(1, ""));
  gltf["buffers"][0].erase("uri");
  write_bytes(dir / "tri.glb", glb(gltf.dump(), 36, triangle_bytes()));
  auto image = load_mesh(dir / "tri.glb");
  ASSERT_TRUE(image.ok()) << image.message();
  EXPECT_GT(covered(*image), 0.05);
}

// FBX: Assimp allocates an array property's declared element count before inflating it, and
// reserves an ASCII array's "*N" before reading it.
std::string u32_le(uint32_t v) {
  return {static_cast<char>(v), static_cast<char>(v >> 8), static_cast<char>(v >> 16),
          static_cast<char>(v >> 24)};
}

struct FbxRecord {
  std::string name;
  std::string properties;  // encoded
  uint32_t property_count = 0;
  std::vector<FbxRecord> children;
};

// A binary FBX 7.4 record starting at byte `at`, with its children and their null record.
std::string fbx_bytes(const FbxRecord& record, uint64_t at) {
  std::string body = record.properties;
  if (!record.children.empty()) {
    uint64_t child_at = at + 13 + record.name.size() + body.size();
    for (const FbxRecord& child : record.children) {
      const std::string bytes = fbx_bytes(child, child_at);
      body += bytes;
      child_at += bytes.size();
    }
    body += std::string(13, '\0');
  }
  const uint64_t end = at + 13 + record.name.size() + body.size();
  return u32_le(static_cast<uint32_t>(end)) + u32_le(record.property_count) +
         u32_le(static_cast<uint32_t>(record.properties.size())) +
         static_cast<char>(record.name.size()) + record.name + body;
}

std::string fbx_file(uint32_t vertex_count, uint32_t encoding, const std::string& stored) {
  const std::string vertices = "d" + u32_le(vertex_count) + u32_le(encoding) +
                               u32_le(static_cast<uint32_t>(stored.size())) + stored;
  const FbxRecord header{"FBXHeaderExtension", "", 0, {{"FBXVersion", "I" + u32_le(7400), 1, {}}}};
  const FbxRecord objects{
      "Objects",
      "",
      0,
      {{"Geometry", "S" + u32_le(4) + "Mesh", 1, {{"Vertices", vertices, 1, {}}}}}};
  std::string file = std::string("Kaydara FBX Binary  \0\x1a\0", 23) + u32_le(7400);
  file += fbx_bytes(header, file.size());
  file += fbx_bytes(objects, file.size());
  return file + std::string(13, '\0') + std::string(16, '\0');
}

TEST(MeshDeclaredSizes, FbxArrayDeclaringHalfABillionDoublesIsRefused) {
  const fs::path dir = scratch_dir("bad_input_fbx_array");
  write_bytes(dir / "forged.fbx", fbx_file(500000000u, 1, std::string(16, 'x')));
  ASSERT_LT(fs::file_size(dir / "forged.fbx"), 512u);
  auto image = load_mesh(dir / "forged.fbx");
  ASSERT_FALSE(image.ok());
  EXPECT_TRUE(mentions(image.message(), "forged.fbx")) << image.message();
  EXPECT_TRUE(mentions(image.message(), "500000000 elements in 16 stored bytes"))
      << image.message();
}

// The same structure with an honest array passes the check: Assimp itself then finds no
// mesh in it, and says so in its own words.
TEST(MeshDeclaredSizes, HonestFbxStructurePassesTheCheck) {
  const fs::path dir = scratch_dir("bad_input_fbx_honest");
  write_bytes(dir / "honest.fbx", fbx_file(9, 0, std::string(72, '\0')));
  auto image = load_mesh(dir / "honest.fbx");
  if (!image.ok()) {
    EXPECT_FALSE(mentions(image.message(), "truncated or forged")) << image.message();
    EXPECT_FALSE(mentions(image.message(), "stored bytes")) << image.message();
  }
}

TEST(MeshDeclaredSizes, AsciiFbxArrayLargerThanTheFileIsRefused) {
  const fs::path dir = scratch_dir("bad_input_fbx_ascii");
  write_bytes(dir / "forged.fbx",
              "; FBX 7.4.0 project file\nObjects:  {\n  Geometry: 1, \"Geometry::\", \"Mesh\" {\n"
              "    Vertices: *4000000000 {\n      a: 0,0,0\n    }\n  }\n}\n");
  auto image = load_mesh(dir / "forged.fbx");
  ASSERT_FALSE(image.ok());
  EXPECT_TRUE(mentions(image.message(), "forged.fbx")) << image.message();
  EXPECT_TRUE(mentions(image.message(), "4000000000 values")) << image.message();
}

// Item 4.
const char* kSecret = "SECRET-LINE-root:x:0:0";

TEST(MeshReferences, MtllibOutsideTheFolderIsRefusedByNameWithoutItsContent) {
  const fs::path root = scratch_dir("bad_input_mtl_outside");
  fs::create_directories(root / "models");
  write_bytes(root / "shadow", std::string(kSecret) + "\nnewmtl x\nKd 1 0 0\n");
  write_bytes(root / "models" / "box.obj",
              "mtllib ../shadow\nusemtl x\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
  auto image = load_mesh(root / "models" / "box.obj");
  ASSERT_FALSE(image.ok());
  EXPECT_TRUE(mentions(image.message(), "../shadow")) << image.message();
  EXPECT_TRUE(mentions(image.message(), "outside the mesh's folder")) << image.message();
  EXPECT_FALSE(mentions(image.message(), "SECRET")) << image.message();
}

TEST(MeshReferences, GltfBufferUriOutsideTheFolderIsRefused) {
  const fs::path root = scratch_dir("bad_input_gltf_outside");
  fs::create_directories(root / "models");
  write_bytes(root / "passwd", std::string(kSecret) + std::string(64, 'x'));
  write_bytes(root / "models" / "tri.gltf", gltf_chain(1, "../passwd"));
  auto image = load_mesh(root / "models" / "tri.gltf");
  ASSERT_FALSE(image.ok());
  EXPECT_TRUE(mentions(image.message(), "../passwd")) << image.message();
  EXPECT_FALSE(mentions(image.message(), "SECRET")) << image.message();
}

TEST(MeshReferences, SymlinkInsideTheFolderPointingOutIsRefused) {
  const fs::path root = scratch_dir("bad_input_symlink_outside");
  fs::create_directories(root / "models");
  write_bytes(root / "outside.bin", triangle_bytes());
  fs::create_symlink(root / "outside.bin", root / "models" / "tri.bin");
  write_bytes(root / "models" / "tri.gltf", gltf_chain(1, "tri.bin"));
  auto image = load_mesh(root / "models" / "tri.gltf");
  ASSERT_FALSE(image.ok());
  EXPECT_TRUE(mentions(image.message(), "tri.bin")) << image.message();
}

TEST(MeshReferences, BufferBesideTheMeshLoads) {
  const fs::path dir = scratch_dir("bad_input_gltf_beside");
  write_bytes(dir / "tri.bin", triangle_bytes());
  write_bytes(dir / "tri.gltf", gltf_chain(1, "tri.bin"));
  auto image = load_mesh(dir / "tri.gltf");
  ASSERT_TRUE(image.ok()) << image.message();
  EXPECT_GT(covered(*image), 0.05);
}

// Item 6: a regular 200,000-gon (a disc of radius 1 facing the camera) is fanned in linear
// time and covers what a disc covers; a large concave polygon is refused with the limit.
TEST(MeshPolygons, TwoHundredThousandVertexConvexPolygonDrawsTheDisc) {
  const fs::path dir = scratch_dir("bad_input_big_polygon");
  const int n = 200000;
  std::string obj;
  obj.reserve(static_cast<size_t>(n) * 40);
  char line[96];
  for (int i = 0; i < n; ++i) {
    const double a = 2.0 * M_PI * i / n;
    std::snprintf(line, sizeof(line), "v %.7f %.7f 0\n", std::cos(a), std::sin(a));
    obj += line;
  }
  obj += "f";
  for (int i = 1; i <= n; ++i) obj += " " + std::to_string(i);
  obj += "\n";
  write_bytes(dir / "disc.obj", obj);
  auto image = load_mesh(dir / "disc.obj");
  ASSERT_TRUE(image.ok()) << image.message();
  // The same disc as 64 triangles of a 64-gon covers (nearly) the same pixels.
  std::string small;
  for (int i = 0; i < 64; ++i) {
    const double a = 2.0 * M_PI * i / 64;
    std::snprintf(line, sizeof(line), "v %.7f %.7f 0\n", std::cos(a), std::sin(a));
    small += line;
  }
  small += "f";
  for (int i = 1; i <= 64; ++i) small += " " + std::to_string(i);
  small += "\n";
  write_bytes(dir / "disc64.obj", small);
  auto reference = load_mesh(dir / "disc64.obj");
  ASSERT_TRUE(reference.ok()) << reference.message();
  EXPECT_GT(covered(*image), 0.1);
  EXPECT_NEAR(covered(*image), covered(*reference), 0.01);
}

TEST(MeshPolygons, LargeConcavePolygonIsRefusedWithTheLimit) {
  const fs::path dir = scratch_dir("bad_input_concave_polygon");
  const int n = 6000;  // a star: radii alternate, so it is not convex
  std::string obj;
  char line[96];
  for (int i = 0; i < n; ++i) {
    const double a = 2.0 * M_PI * i / n;
    const double r = i % 2 == 0 ? 1.0 : 0.5;
    std::snprintf(line, sizeof(line), "v %.7f %.7f 0\n", r * std::cos(a), r * std::sin(a));
    obj += line;
  }
  obj += "f";
  for (int i = 1; i <= n; ++i) obj += " " + std::to_string(i);
  obj += "\n";
  write_bytes(dir / "star.obj", obj);
  auto image = load_mesh(dir / "star.obj");
  ASSERT_FALSE(image.ok());
  EXPECT_TRUE(mentions(image.message(), "star.obj")) << image.message();
  EXPECT_TRUE(mentions(image.message(), "6000 vertices")) << image.message();
  EXPECT_TRUE(mentions(image.message(), "4096")) << image.message();
}

}  // namespace
}  // namespace aq::test::bad_input
