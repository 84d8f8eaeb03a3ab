// Round three (issue 40), class 5: small files that made `aquarelle render` take more than 1 GB
// (and class 3/4 cases of the same kind: seconds of work or bad_alloc from a few kilobytes).
// Each test writes the hostile file (a few KB, made here), renders a graph that reads it
// through the real command line, and asserts: exit 1, one line naming the file, within
// seconds, and a peak resident size of the process under 1 GB (wait4's rusage). The EGL
// context alone takes about 200 MB.
#include <zlib.h>

#include <aquarelle/core/color.h>
#include <aquarelle/core/image_io.h>

#include <cmath>
#include <cstdio>
#include <cstring>
#include <utility>

#include "bad_input/bad_input_support.h"

namespace aq::test::bad_input {
namespace {

constexpr long kOneGigabyteKib = 1000L * 1000L;

bool mentions(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}

std::string deflate(const std::string& raw) {
  uLongf size = compressBound(raw.size());
  std::string out(size, '\0');
  EXPECT_EQ(compress2(reinterpret_cast<Bytef*>(out.data()), &size,
                      reinterpret_cast<const Bytef*>(raw.data()), raw.size(), 9),
            Z_OK);
  out.resize(size);
  return out;
}

// A w x h PNG of `bit_depth`-bit greyscale, every pixel 0: compresses to almost nothing.
std::string blank_png(uint32_t w, uint32_t h, int bit_depth) {
  const size_t row = 1 + (static_cast<size_t>(w) * bit_depth + 7) / 8;
  const std::string ihdr =
      big_endian(w) + big_endian(h) + std::string{static_cast<char>(bit_depth), 0, 0, 0, 0};
  return std::string("\x89PNG\r\n\x1a\n", 8) + png_chunk("IHDR", ihdr) +
         png_chunk("IDAT", deflate(std::string(row * h, '\0'))) + png_chunk("IEND", "");
}

std::string read_graph(const std::string& file) {
  return R"({"aquarelle": 1, "settings": {"width": 64, "height": 64, "frames": [1, 1]},
  "nodes": {"source": {"type": "read", "params": {"path": ")" +
         file + R"("}}}, "output": "source.image"})";
}

// Renders GRAPH (in `dir`) and checks the refusal: exit 1, one line naming `file`, quick, small.
void expect_refused_quickly(const fs::path& dir, const std::string& graph, const std::string& file,
                            const std::string& reason) {
  write_bytes(dir / "g.json", graph);
  const MeasuredRun run = aquarelle_measured(
      60, "render " + (dir / "g.json").string() + " -q -o " + (dir / "out.exr").string());
  EXPECT_EQ(run.exit_code, 1) << run.output;
  EXPECT_EQ(line_count(run.output), 1) << run.output;
  EXPECT_TRUE(mentions(run.output, file)) << run.output;
  EXPECT_TRUE(mentions(run.output, reason)) << run.output;
  EXPECT_LT(run.seconds, 20.0) << run.output;
  EXPECT_LT(run.peak_kib, kOneGigabyteKib) << run.output;
  EXPECT_FALSE(fs::exists(dir / "out.exr"));
}

// Renders a graph drawing mesh `file` (in `dir`) and checks it is accepted: exit 0, quick, small.
void expect_renders_quickly(const fs::path& dir, const std::string& file) {
  write_bytes(dir / "g.json", mesh_graph(file));
  const MeasuredRun run = aquarelle_measured(
      60, "render " + (dir / "g.json").string() + " -q -o " + (dir / "out.exr").string());
  EXPECT_EQ(run.exit_code, 0) << run.output;
  EXPECT_LT(run.seconds, 20.0) << run.output;
  EXPECT_LT(run.peak_kib, kOneGigabyteKib) << run.output;
}

// 8 KB, 8192x8192 of 1 bit: 2.9 GB once decoded to floats (every channel, every copy).
TEST(SmallFilesLargeMemory, OneBitPngOf8192SquaredIsBudgetedDecoded) {
  const fs::path dir = scratch_dir("bad_input_mem_onebit_png");
  write_bytes(dir / "onebit.png", blank_png(8192, 8192, 1));
  ASSERT_LT(fs::file_size(dir / "onebit.png"), 10000u);
  expect_refused_quickly(dir, read_graph("onebit.png"), "onebit.png", "memory budget");
}

// 24 KB, 14000x14000: was an uncaught std::bad_alloc (class 4).
TEST(SmallFilesLargeMemory, PngOf14000SquaredIsExitOneNotBadAlloc) {
  const fs::path dir = scratch_dir("bad_input_mem_14000_png");
  write_bytes(dir / "wide.png", blank_png(14000, 14000, 1));
  ASSERT_LT(fs::file_size(dir / "wide.png"), 30000u);
  expect_refused_quickly(dir, read_graph("wide.png"), "wide.png", "14000x14000");
}

std::string u16(uint16_t v) {
  return std::string(reinterpret_cast<const char*>(&v), 2);
}
std::string u32(uint32_t v) {
  return std::string(reinterpret_cast<const char*>(&v), 4);
}

// A little-endian greyscale 8-bit TIFF of one strip holding `strip` (compression as TIFF
// numbers it: 1 none, 8 deflate, 32773 PackBits).
std::string tiff_one_strip(uint32_t w, uint32_t h, uint16_t compression, const std::string& strip) {
  struct Entry {
    uint16_t tag, type;
    uint32_t value;
  };
  const uint32_t data_at = 8 + 2 + 11 * 12 + 4;
  const Entry entries[] = {{256, 4, w},           {257, 4, h}, {258, 3, 8},
                           {259, 3, compression}, {262, 3, 1}, {273, 4, data_at},
                           {277, 3, 1},           {278, 4, h}, {279, 4, uint32_t(strip.size())},
                           {284, 3, 1},           {339, 3, 1}};
  std::string tiff = "II*" + std::string(1, '\0') + u32(8) + u16(11);
  for (const Entry& e : entries) tiff += u16(e.tag) + u16(e.type) + u32(1) + u32(e.value);
  return tiff + u32(0) + strip;
}

// 130-odd bytes declaring 8000x8000 (one deflated row): 2.75 GB before.
TEST(SmallFilesLargeMemory, TinyTiffDeclaring8000SquaredIsRefused) {
  const fs::path dir = scratch_dir("bad_input_mem_tiff");
  write_bytes(dir / "huge.tif", tiff_one_strip(8000, 8000, 8, deflate(std::string(8000, '\x80'))));
  ASSERT_LT(fs::file_size(dir / "huge.tif"), 200u);
  expect_refused_quickly(dir, read_graph("huge.tif"), "huge.tif", "8000x8000");
}

// A 1000x1000 TIFF whose only strip holds one row (deflate, then PackBits), or that lists no
// strip for its last rows: OpenImageIO read the missing rows as black and reported success.
TEST(TruncatedImages, TiffStripsShorterThanTheirRowsAreAnErrorNamingTheFile) {
  std::string packbits_row;  // 1000 bytes of 0x80: seven runs of 128, one of 104
  for (int i = 0; i < 7; ++i) packbits_row += std::string{'\x81', '\x80'};
  packbits_row += std::string{static_cast<char>(256 - 103), '\x80'};
  const std::pair<const char*, std::string> files[] = {
      {"deflate.tif", tiff_one_strip(1000, 1000, 8, deflate(std::string(1000, '\x80')))},
      {"packbits.tif", tiff_one_strip(1000, 1000, 32773, packbits_row)}};
  for (const auto& [name, bytes] : files) {
    const fs::path dir = scratch_dir(std::string("bad_input_truncated_") + name);
    write_bytes(dir / name, bytes);
    expect_refused_quickly(dir, read_graph(name), name, "truncated");
  }
}

// The same strip holding all its rows reads, with the right value (0x80 in sRGB).
TEST(TruncatedImages, CompleteDeflatedTiffReads) {
  const fs::path dir = scratch_dir("bad_input_truncated_complete");
  write_bytes(
      dir / "whole.tif",
      tiff_one_strip(64, 64, 8, deflate(std::string(64, '\x80') + std::string(64 * 63, '\x80'))));
  write_bytes(dir / "g.json", read_graph("whole.tif"));
  const MeasuredRun run = aquarelle_measured(
      60, "render " + (dir / "g.json").string() + " -q -o " + (dir / "out.exr").string());
  ASSERT_EQ(run.exit_code, 0) << run.output;
  auto config = ColorConfig::load();
  ASSERT_TRUE(config.ok()) << config.message();
  auto image = read_image((dir / "out.exr").string(), *config);
  ASSERT_TRUE(image.ok()) << image.message();
  const double linear = std::pow((128.0 / 255.0 + 0.055) / 1.055, 2.4);
  EXPECT_NEAR(image->at(10, 50, 0), linear, 2e-3);
  EXPECT_NEAR(image->at(63, 0, 1), linear, 2e-3) << "the last row is not black";
}

// 220 bytes: one face declaring 268 M indices (binary), 2.2 GB before.
TEST(SmallFilesLargeMemory, BinaryPlyFaceDeclaring268MIndicesIsRefused) {
  const fs::path dir = scratch_dir("bad_input_mem_ply_binary");
  std::string ply =
      "ply\nformat binary_little_endian 1.0\nelement vertex 3\nproperty float x\n"
      "property float y\nproperty float z\nelement face 1\n"
      "property list uint int vertex_indices\nend_header\n";
  ply += triangle_bytes() + u32(268435456u) + u32(0) + u32(1) + u32(2);
  write_bytes(dir / "face.ply", ply);
  ASSERT_LE(fs::file_size(dir / "face.ply"), 220u);
  expect_refused_quickly(dir, mesh_graph("face.ply"), "face.ply", "268435456 items");
}

// The same in ASCII: the list count was not walked (4.4 GB and 12 s before).
TEST(SmallFilesLargeMemory, AsciiPlyFaceDeclaring268MIndicesIsRefused) {
  const fs::path dir = scratch_dir("bad_input_mem_ply_ascii");
  write_bytes(dir / "face.ply",
              "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
              "property float z\nelement face 1\nproperty list uint int vertex_indices\n"
              "end_header\n-1 -1 0\n1 -1 0\n0 1 0\n268435456 0 1 2\n");
  expect_refused_quickly(dir, mesh_graph("face.ply"), "face.ply", "268435456 items");
}

// An honest ASCII PLY with comments and a quad still loads (the walk follows the header).
TEST(SmallFilesLargeMemory, HonestAsciiPlyStillLoads) {
  const fs::path dir = scratch_dir("bad_input_mem_ply_ascii_ok");
  write_bytes(dir / "quad.ply",
              "ply\nformat ascii 1.0\ncomment made by hand\nelement vertex 4\nproperty float x\n"
              "property float y\nproperty float z\nelement face 1\n"
              "property list uchar int vertex_indices\nend_header\n-1 -1 0\n1 -1 0\n1 1 0\n"
              "-1 1 0\n4 0 1 2 3\n");
  auto image = load_mesh(dir / "quad.ply");
  ASSERT_TRUE(image.ok()) << image.message();
  EXPECT_GT(covered(*image), 0.05);
}

// A glTF accessor of `count` points, all zero but one sparse value (about 600 bytes).
std::string sparse_points_gltf(uint64_t count) {
  const std::string buffer = triangle_bytes() + u32(0);
  nlohmann::json gltf = {
      {"asset", {{"version", "2.0"}}},
      {"scene", 0},
      {"scenes", {{{"nodes", {0}}}}},
      {"nodes", {{{"mesh", 0}}}},
      {"meshes", {{{"primitives", {{{"attributes", {{"POSITION", 0}}}, {"mode", 0}}}}}}},
      {"buffers", {{{"byteLength", buffer.size()}, {"uri", data_uri(buffer)}}}},
      {"bufferViews",
       {{{"buffer", 0}, {"byteOffset", 0}, {"byteLength", 36}},
        {{"buffer", 0}, {"byteOffset", 36}, {"byteLength", 4}}}},
      {"accessors",
       {{{"componentType", 5126},
         {"count", count},
         {"type", "VEC3"},
         {"min", {-1, -1, 0}},
         {"max", {1, 1, 0}},
         {"sparse",
          {{"count", 1},
           {"indices", {{"bufferView", 1}, {"componentType", 5125}}},
           {"values", {{"bufferView", 0}}}}}}}}};
  return gltf.dump();
}

// 100 M points took 2.5 GB; 40 M passed the old per-accessor check (16 bytes each) and took
// 3.3 GB in 20 s: the check now counts what Assimp makes of each element.
TEST(SmallFilesLargeMemory, SparseGltfAccessorsAreBudgetedAsAssimpHoldsThem) {
  for (const uint64_t count : {100000000ull, 40000000ull}) {
    const fs::path dir = scratch_dir("bad_input_mem_gltf_" + std::to_string(count));
    write_bytes(dir / "sparse.gltf", sparse_points_gltf(count));
    ASSERT_LT(fs::file_size(dir / "sparse.gltf"), 700u);
    expect_refused_quickly(dir, mesh_graph("sparse.gltf"), "sparse.gltf",
                           "accessor 0 declares " + std::to_string(count) + " elements");
  }
}

// 150,000 one-triangle objects in 2.6 MB took 1.5 GB and 37 s.
TEST(SmallFilesLargeMemory, ObjOf150000ObjectsIsRefused) {
  const fs::path dir = scratch_dir("bad_input_mem_obj_objects");
  std::string obj = "v 0 0 0\nv 1 0 0\nv 0 1 0\n";
  for (int i = 0; i < 150000; ++i) obj += "o t" + std::to_string(i) + "\nf 1 2 3\n";
  write_bytes(dir / "many.obj", obj);
  ASSERT_LT(fs::file_size(dir / "many.obj"), 2700000u);
  expect_refused_quickly(dir, mesh_graph("many.obj"), "many.obj", "150000 objects");
}

// The same triangles in one object are a normal mesh, but every corner lies on one of three
// points: the scene's normal smoothing compared each vertex with all earlier ones in its weld
// cell (quadratic: 30,000 triangles 20 s, 150,000 several minutes). It renders in seconds.
TEST(SmallFilesLargeMemory, CoincidentTrianglesRenderInSeconds) {
  const fs::path dir = scratch_dir("bad_input_mem_obj_coincident");
  std::string obj = "v -1 -1 0\nv 1 -1 0\nv 0 1 0\n";
  for (int i = 0; i < 150000; ++i) obj += "f 1 2 3\n";
  write_bytes(dir / "same.obj", obj);
  expect_renders_quickly(dir, "same.obj");
}

// Distinct corners instead of shared ones: 150,000 vertices crowded within the weld tolerance
// (1e-5 of the mesh's size, which one far triangle makes large), every one compared with all
// earlier ones in its cell (over a minute). It renders in seconds.
TEST(SmallFilesLargeMemory, CrowdedDistinctVerticesRenderInSeconds) {
  const fs::path dir = scratch_dir("bad_input_mem_obj_crowded");
  std::string obj = "v -1 -1 0\nv 1 -1 0\nv 0 1 0\nv 20000 0 0\n";
  for (int i = 0; i < 150000; ++i) {
    // Distinct floats inside a 0.02-wide cube; the tolerance is 1e-5 x 20000 = 0.2.
    char line[96];
    std::snprintf(line, sizeof line, "v %.9g %.9g %.9g\n", 1e-7 * i, 1.3e-7 * (i % 1000),
                  0.01 + 1.7e-7 * (i % 777));
    obj += line;
  }
  obj += "f 1 2 3\nf 1 2 4\n";
  for (int i = 0; i < 150000; i += 3)
    obj += "f " + std::to_string(5 + i) + " " + std::to_string(6 + i) + " " +
           std::to_string(7 + i) + "\n";
  write_bytes(dir / "crowd.obj", obj);
  expect_renders_quickly(dir, "crowd.obj");
}

// 400,000 unconnected nodes (11 MB of JSON) took 10 s and 720 MB and printed 400,000 lines;
// a graph file holds at most kMaxGraphFileNodes, refused in one line.
TEST(SmallFilesLargeMemory, GraphOfManyUnusedNodesIsRefusedInOneLine) {
  const fs::path dir = scratch_dir("bad_input_mem_many_nodes");
  std::string graph = R"({"aquarelle": 1, "settings": {"width": 16, "height": 16}, "nodes": {)";
  for (int i = 0; i < 400000; ++i) graph += "\"n" + std::to_string(i) + R"(": {"type": "tint"},)";
  graph += R"("src": {"type": "read", "params": {"path": "x.png"}}}, "output": "src.image"})";
  write_bytes(dir / "g.json", graph);
  const MeasuredRun run = aquarelle_measured(
      60, "render " + (dir / "g.json").string() + " -q -o " + (dir / "out.exr").string());
  EXPECT_EQ(run.exit_code, 1) << run.output.substr(0, 2000);
  EXPECT_EQ(line_count(run.output), 1) << run.output.substr(0, 2000);
  EXPECT_TRUE(mentions(run.output, "400001 nodes")) << run.output.substr(0, 2000);
  EXPECT_LT(run.seconds, 20.0);
  EXPECT_LT(run.peak_kib, kOneGigabyteKib / 2);
}

}  // namespace
}  // namespace aq::test::bad_input
