// Headless tests of the `object` and `scene_join` nodes through the g-buffer: each material
// case (OBJ Kd, OBJ map_Kd x Kd, glTF baseColorTexture embedded and beside the file x base
// colour x vertex colours, a colour override, a missing texture or material file) and each
// transform case (position, rotation, scale; fit) against the CPU reference of the albedo in
// reference/scene_albedo.h; texture alpha as cut-outs in the g-buffer and the shadow
// map; keyframe and swim animation; several objects joined with their own ids.
#include <gtest/gtest.h>

#include <aquarelle/core/image_io.h>

#include <glm/gtc/matrix_transform.hpp>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <set>
#include <string>
#include <vector>

#include "aquarelle/reference/scene_albedo.h"
#include "support/harness.h"

namespace {

namespace fs = std::filesystem;
using aq::ImageF;
using aq::reference::RefCamera;
using aq::reference::RefTexture;
using aq::reference::RefTriangle;

const RefCamera kCamera{{0.3, 2.2, 2.0}, {0.0, 0.0, 0.0}, 45.0};
constexpr int kSize = 96;

fs::path scratch(const std::string& name) {
  fs::path dir = fs::temp_directory_path() / ("aq_object_test_" + std::to_string(getpid())) / name;
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

void write_text(const fs::path& path, const std::string& text) {
  std::ofstream(path, std::ios::binary) << text;
}

// An 8-bit sRGB RGBA PNG of w x h texels with values k/255 (transparent texels black), and the
// linear texels a reader of it must see.
RefTexture write_png(const fs::path& path, int w, int h, unsigned seed, bool with_holes) {
  ImageF image(w, h, 4);
  RefTexture texture{w, h, {}};
  unsigned state = seed * 2654435761u + 1;
  auto next = [&]() {
    state = state * 1664525u + 1013904223u;
    return static_cast<int>((state >> 8) % 256);
  };
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      int code[4] = {next(), next(), next(), 255};
      if (with_holes && x < w / 2) code[0] = code[1] = code[2] = code[3] = 0;
      glm::dvec4 linear(0.0);
      for (int c = 0; c < 4; ++c) {
        image.at(x, y, c) = static_cast<float>(code[c] / 255.0);
        linear[c] = c < 3 ? aq::reference::srgb_to_linear(code[c] / 255.0) : code[c] / 255.0;
      }
      texture.texels.push_back(linear);
    }
  }
  aq::WriteOptions options;
  options.bits = 8;
  EXPECT_TRUE(aq::write_image(path.string(), image, options).ok());
  return texture;
}

// A quad in the y = 0 plane (a x a, centred), uvs 0..1 with v growing towards -z.
struct Quad {
  glm::dvec3 p[4] = {{-0.5, 0, 0.5}, {0.5, 0, 0.5}, {0.5, 0, -0.5}, {-0.5, 0, -0.5}};
  glm::dvec2 uv[4] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
  glm::dvec3 color[4] = {glm::dvec3(1), glm::dvec3(1), glm::dvec3(1), glm::dvec3(1)};
};

std::vector<RefTriangle> triangles_of(const Quad& q, const RefTexture* texture, double cutoff,
                                      const glm::dmat4& transform = glm::dmat4(1.0)) {
  std::vector<RefTriangle> out;
  for (auto [a, b, c] : {std::array{0, 1, 2}, std::array{0, 2, 3}}) {
    RefTriangle t;
    int index[3] = {a, b, c};
    for (int k = 0; k < 3; ++k) {
      t.p[k] = glm::dvec3(transform * glm::dvec4(q.p[index[k]], 1.0));
      t.uv[k] = q.uv[index[k]];
      t.color[k] = q.color[index[k]];
    }
    t.texture = texture;
    t.alpha_cutoff = cutoff;
    out.push_back(t);
  }
  return out;
}

std::string obj_quad(const Quad& q, const std::string& mtllib) {
  std::string text = mtllib.empty() ? "" : "mtllib " + mtllib + "\nusemtl m\n";
  for (const auto& p : q.p) {
    text +=
        "v " + std::to_string(p.x) + " " + std::to_string(p.y) + " " + std::to_string(p.z) + "\n";
  }
  for (const auto& t : q.uv) text += "vt " + std::to_string(t.x) + " " + std::to_string(t.y) + "\n";
  text += "vn 0 1 0\nf 1/1/1 2/2/1 3/3/1\nf 1/1/1 3/3/1 4/4/1\n";
  return text;
}

std::string base64(const std::string& bytes) {
  static const char* table = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  size_t i = 0;
  for (; i + 2 < bytes.size(); i += 3) {
    unsigned n = (static_cast<unsigned char>(bytes[i]) << 16) |
                 (static_cast<unsigned char>(bytes[i + 1]) << 8) |
                 static_cast<unsigned char>(bytes[i + 2]);
    for (int k = 3; k >= 0; --k) out += table[(n >> (6 * k)) & 63];
  }
  if (i < bytes.size()) {
    unsigned n = static_cast<unsigned char>(bytes[i]) << 16;
    if (i + 1 < bytes.size()) n |= static_cast<unsigned char>(bytes[i + 1]) << 8;
    out += table[(n >> 18) & 63];
    out += table[(n >> 12) & 63];
    out += i + 1 < bytes.size() ? table[(n >> 6) & 63] : '=';
    out += '=';
  }
  return out;
}

std::string read_bytes(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

// A glTF quad with vertex colours, a base colour factor and a texture (`image_uri`). glTF's v
// runs down the image, so its uv is (u, 1 - v) of the quad's.
void write_gltf_quad(const fs::path& path, const Quad& q, const glm::dvec3& factor,
                     const std::string& image_uri) {
  std::string blob;
  auto put = [&](float f) { blob.append(reinterpret_cast<const char*>(&f), 4); };
  for (const auto& p : q.p) put(float(p.x)), put(float(p.y)), put(float(p.z));
  for (int i = 0; i < 4; ++i) put(0), put(1), put(0);
  for (const auto& t : q.uv) put(float(t.x)), put(float(1.0 - t.y));
  for (const auto& c : q.color) put(float(c.r)), put(float(c.g)), put(float(c.b)), put(1.0f);
  const uint16_t indices[6] = {0, 1, 2, 0, 2, 3};
  blob.append(reinterpret_cast<const char*>(indices), sizeof(indices));
  nlohmann::json doc = {
      {"asset", {{"version", "2.0"}}},
      {"scene", 0},
      {"scenes", {{{"nodes", {0}}}}},
      {"nodes", {{{"mesh", 0}}}},
      {"meshes",
       {{{"primitives",
          {{{"attributes", {{"POSITION", 0}, {"NORMAL", 1}, {"TEXCOORD_0", 2}, {"COLOR_0", 3}}},
            {"indices", 4},
            {"material", 0}}}}}}},
      {"materials",
       {{{"name", "m"},
         {"pbrMetallicRoughness",
          {{"baseColorFactor", {factor.r, factor.g, factor.b, 1.0}},
           {"baseColorTexture", {{"index", 0}}}}}}}},
      {"textures", {{{"source", 0}}}},
      {"images", {{{"uri", image_uri}}}},
      {"buffers",
       {{{"byteLength", blob.size()},
         {"uri", "data:application/octet-stream;base64," + base64(blob)}}}},
      {"bufferViews",
       {{{"buffer", 0}, {"byteOffset", 0}, {"byteLength", 48}},
        {{"buffer", 0}, {"byteOffset", 48}, {"byteLength", 48}},
        {{"buffer", 0}, {"byteOffset", 96}, {"byteLength", 32}},
        {{"buffer", 0}, {"byteOffset", 128}, {"byteLength", 64}},
        {{"buffer", 0}, {"byteOffset", 192}, {"byteLength", 12}}}},
      {"accessors",
       {{{"bufferView", 0},
         {"componentType", 5126},
         {"count", 4},
         {"type", "VEC3"},
         {"min", {-0.5, 0, -0.5}},
         {"max", {0.5, 0, 0.5}}},
        {{"bufferView", 1}, {"componentType", 5126}, {"count", 4}, {"type", "VEC3"}},
        {{"bufferView", 2}, {"componentType", 5126}, {"count", 4}, {"type", "VEC2"}},
        {{"bufferView", 3}, {"componentType", 5126}, {"count", 4}, {"type", "VEC4"}},
        {{"bufferView", 4}, {"componentType", 5123}, {"count", 6}, {"type", "SCALAR"}}}}};
  write_text(path, doc.dump());
}

nlohmann::json join_graph(const nlohmann::json& objects, const std::string& output,
                          const RefCamera& camera = kCamera) {
  nlohmann::json nodes = nlohmann::json::object();
  nlohmann::json links = nlohmann::json::array();
  for (const auto& [id, params] : objects.items()) {
    nodes[id] = {{"type", "object"}, {"params", params}};
    links.push_back(id + ".object");
  }
  nodes["join"] = {{"type", "scene_join"},
                   {"params",
                    {{"camera_position", {camera.eye.x, camera.eye.y, camera.eye.z}},
                     {"camera_target", {camera.target.x, camera.target.y, camera.target.z}},
                     {"fov", camera.fov_y_degrees},
                     {"environment", "none"}}},
                   {"inputs", {{"objects", links}}}};
  nodes["gbuf"] = {{"type", "gbuffer"}, {"inputs", {{"scene", "join.scene"}}}};
  return {{"aquarelle", 1}, {"nodes", nodes}, {"output", output}};
}

ImageF render(const nlohmann::json& graph, const std::string& output = "gbuf.albedo",
              int frame = 1) {
  aq::test::RenderOptions options;
  options.width = kSize;
  options.height = kSize;
  options.output = output;
  options.frame = frame;
  auto image = aq::test::render_graph(graph.dump(), options);
  EXPECT_TRUE(image.ok()) << (image.ok() ? "" : image.message());
  return image.ok() ? *image : ImageF();
}

struct Comparison {
  double max_error = 0.0;
  int compared = 0;
  int coverage_mismatches = 0;
};

// The rendered albedo against the reference at every pixel whose footprint is all object or
// all background (and not on a cut-out's edge).
Comparison compare(const ImageF& albedo, const std::vector<RefTriangle>& triangles,
                   const RefCamera& camera = kCamera) {
  Comparison result;
  for (int y = 0; y < albedo.height; ++y) {
    for (int x = 0; x < albedo.width; ++x) {
      auto centre =
          aq::reference::reference_albedo(triangles, camera, albedo.width, albedo.height, x, y);
      bool mixed = false;
      for (auto [dx, dy] : {std::pair{-0.5, -0.5}, {0.5, -0.5}, {-0.5, 0.5}, {0.5, 0.5}}) {
        auto corner = aq::reference::reference_albedo(triangles, camera, albedo.width,
                                                      albedo.height, x, y, dx, dy);
        mixed |= corner.has_value() != centre.has_value();
      }
      if (mixed) continue;
      if (centre && centre->alpha < 1.0 && triangles[centre->triangle].alpha_cutoff > 0.0 &&
          std::abs(centre->alpha - triangles[centre->triangle].alpha_cutoff) < 0.2) {
        continue;
      }
      const bool covered = albedo.at(x, y, 3) == 1.0f;
      if (covered != centre.has_value()) {
        ++result.coverage_mismatches;
        continue;
      }
      if (!centre) continue;
      for (int c = 0; c < 3; ++c) {
        result.max_error =
            std::max(result.max_error, std::abs(albedo.at(x, y, c) - centre->albedo[c]));
      }
      ++result.compared;
    }
  }
  return result;
}

void expect_matches(const Comparison& c, int min_compared = 900) {
  std::printf("albedo vs reference: %d pixels, max error %.2e\n", c.compared, c.max_error);
  EXPECT_GE(c.compared, min_compared);
  EXPECT_EQ(c.coverage_mismatches, 0);
  // Texels are RGBA16F (relative step 2^-11) and filtered by llvmpipe: measured <= 4.7e-4
  // textured, 2e-7 untextured.
  EXPECT_LT(c.max_error, 2e-3);
}

TEST(Object, ObjDiffuseColourOnly) {
  const fs::path dir = scratch("kd");
  Quad q;
  write_text(dir / "quad.obj", obj_quad(q, "quad.mtl"));
  write_text(dir / "quad.mtl", "newmtl m\nKd 0.2 0.5 0.7\n");
  for (auto& c : q.color) c = {0.2, 0.5, 0.7};
  ImageF albedo =
      render(join_graph({{"quad", {{"path", (dir / "quad.obj").string()}}}}, "gbuf.albedo"));
  expect_matches(compare(albedo, triangles_of(q, nullptr, 0.0)));
}

TEST(Object, ObjMapKdTimesKd) {
  const fs::path dir = scratch("map_kd");
  Quad q;
  const RefTexture texture = write_png(dir / "tex.png", 4, 4, 1, false);
  write_text(dir / "quad.obj", obj_quad(q, "quad.mtl"));
  write_text(dir / "quad.mtl", "newmtl m\nKd 0.9 0.6 1.0\nmap_Kd tex.png\n");
  for (auto& c : q.color) c = {0.9, 0.6, 1.0};
  ImageF albedo =
      render(join_graph({{"quad", {{"path", (dir / "quad.obj").string()}}}}, "gbuf.albedo"));
  expect_matches(compare(albedo, triangles_of(q, &texture, 0.0)));
}

TEST(Object, GltfEmbeddedTextureTimesBaseColourAndVertexColours) {
  const fs::path dir = scratch("gltf_embedded");
  Quad q;
  q.color[0] = {1.0, 0.5, 0.5};
  q.color[1] = {0.5, 1.0, 0.5};
  q.color[2] = {0.5, 0.5, 1.0};
  q.color[3] = {1.0, 1.0, 1.0};
  const RefTexture texture = write_png(dir / "tex.png", 4, 4, 2, false);
  const std::string png = read_bytes(dir / "tex.png");
  fs::remove(dir / "tex.png");
  const glm::dvec3 factor(0.8, 0.9, 0.7);
  write_gltf_quad(dir / "quad.gltf", q, factor, "data:image/png;base64," + base64(png));
  for (auto& c : q.color) c *= factor;
  ImageF albedo =
      render(join_graph({{"quad", {{"path", (dir / "quad.gltf").string()}}}}, "gbuf.albedo"));
  expect_matches(compare(albedo, triangles_of(q, &texture, 0.0)));
}

TEST(Object, GltfTextureBesideTheFile) {
  const fs::path dir = scratch("gltf_beside");
  Quad q;
  const RefTexture texture = write_png(dir / "tex.png", 4, 4, 3, false);
  write_gltf_quad(dir / "quad.gltf", q, glm::dvec3(1.0), "tex.png");
  ImageF albedo =
      render(join_graph({{"quad", {{"path", (dir / "quad.gltf").string()}}}}, "gbuf.albedo"));
  expect_matches(compare(albedo, triangles_of(q, &texture, 0.0)));
}

TEST(Object, ColourOverrideReplacesKdAndKeepsTheTexture) {
  const fs::path dir = scratch("override");
  Quad q;
  const RefTexture texture = write_png(dir / "tex.png", 4, 4, 4, false);
  write_text(dir / "quad.obj", obj_quad(q, "quad.mtl"));
  write_text(dir / "quad.mtl", "newmtl m\nKd 0.1 0.1 0.1\nmap_Kd tex.png\n");
  for (auto& c : q.color) c = {0.3, 0.9, 0.6};
  ImageF albedo = render(join_graph({{"quad",
                                      {{"path", (dir / "quad.obj").string()},
                                       {"color_override", true},
                                       {"color", {0.3, 0.9, 0.6}}}}},
                                    "gbuf.albedo"));
  expect_matches(compare(albedo, triangles_of(q, &texture, 0.0)));
}

TEST(Object, MissingTextureFallsBackToKd) {
  const fs::path dir = scratch("missing_texture");
  Quad q;
  write_text(dir / "quad.obj", obj_quad(q, "quad.mtl"));
  write_text(dir / "quad.mtl", "newmtl m\nKd 0.4 0.3 0.2\nmap_Kd nowhere.png\n");
  for (auto& c : q.color) c = {0.4, 0.3, 0.2};
  ImageF albedo =
      render(join_graph({{"quad", {{"path", (dir / "quad.obj").string()}}}}, "gbuf.albedo"));
  expect_matches(compare(albedo, triangles_of(q, nullptr, 0.0)));
}

TEST(Object, MissingMaterialFileIsGrey) {
  const fs::path dir = scratch("missing_mtl");
  Quad q;
  write_text(dir / "quad.obj", obj_quad(q, "gone.mtl"));
  for (auto& c : q.color) c = glm::dvec3(0.6);  // Assimp's default material
  ImageF albedo =
      render(join_graph({{"quad", {{"path", (dir / "quad.obj").string()}}}}, "gbuf.albedo"));
  expect_matches(compare(albedo, triangles_of(q, nullptr, 0.0)));
}

// position, rotation (degrees, x then y then z) and scale, on a textured procedural plane.
TEST(Object, PositionRotationAndScale) {
  const fs::path dir = scratch("transform");
  const RefTexture texture = write_png(dir / "tex.png", 4, 4, 5, false);
  const glm::dvec3 position(0.2, 0.1, -0.1), rotation(-10.0, 35.0, 8.0), scale(1.3, 1.0, 0.8);
  glm::dmat4 m = glm::translate(glm::dmat4(1.0), position);
  m = glm::rotate(m, glm::radians(rotation.z), glm::dvec3(0, 0, 1));
  m = glm::rotate(m, glm::radians(rotation.y), glm::dvec3(0, 1, 0));
  m = glm::rotate(m, glm::radians(rotation.x), glm::dvec3(1, 0, 0));
  m = glm::scale(m, scale);
  ImageF albedo = render(join_graph({{"plane",
                                      {{"source", "plane"},
                                       {"texture", (dir / "tex.png").string()},
                                       {"position", {position.x, position.y, position.z}},
                                       {"rotation", {rotation.x, rotation.y, rotation.z}},
                                       {"scale", {scale.x, scale.y, scale.z}}}}},
                                    "gbuf.albedo"));
  expect_matches(compare(albedo, triangles_of(Quad{}, &texture, 0.0, m)), 700);
}

// `fit`: a 6-unit quad 10 units away becomes the unit quad at the origin.
TEST(Object, FitFramesTheObjectInAUnitBox) {
  const fs::path dir = scratch("fit");
  Quad big;
  for (auto& p : big.p) p = p * 6.0 + glm::dvec3(10.0, 3.0, -7.0);
  write_text(dir / "big.obj", obj_quad(big, "big.mtl"));
  write_text(dir / "big.mtl", "newmtl m\nKd 0.5 0.6 0.7\n");
  Quad unit;
  for (auto& c : unit.color) c = {0.5, 0.6, 0.7};
  ImageF albedo = render(
      join_graph({{"quad", {{"path", (dir / "big.obj").string()}, {"fit", true}}}}, "gbuf.albedo"));
  expect_matches(compare(albedo, triangles_of(unit, nullptr, 0.0)));
}

// Texels with alpha under the cut-off are holes: background in the g-buffer.
TEST(Object, AlphaCutsOutInTheGBuffer) {
  const fs::path dir = scratch("cutout");
  const RefTexture texture = write_png(dir / "card.png", 4, 4, 6, true);
  ImageF albedo = render(join_graph(
      {{"plane",
        {{"source", "plane"}, {"texture", (dir / "card.png").string()}, {"alpha_cutoff", 0.5}}}},
      "gbuf.albedo"));
  const Comparison c = compare(albedo, triangles_of(Quad{}, &texture, 0.5));
  expect_matches(c, 350);
  int holes = 0;  // pixels of the quad's left half that show the background
  for (int y = 0; y < albedo.height; ++y) {
    for (int x = 0; x < albedo.width; ++x) {
      auto hit = aq::reference::reference_albedo(triangles_of(Quad{}, &texture, 0.0), kCamera,
                                                 kSize, kSize, x, y);
      if (hit && hit->alpha == 0.0 && albedo.at(x, y, 3) == 0.0f) ++holes;
    }
  }
  EXPECT_GT(holes, 250);
}

// The same holes let the light through in the shadow map: looking straight down at a card
// whose texture is holes on one half (u < 0.5), over a floor, one half of the map sees the
// card and the other the floor below it; an opaque card (cut-off 0) is seen all over.
TEST(Object, AlphaCutsOutInTheShadowMap) {
  const fs::path dir = scratch("cutout_shadow");
  write_png(dir / "card.png", 4, 4, 7, true);
  auto halves = [&](double cutoff) {
    nlohmann::json graph =
        join_graph({{"plane",
                     {{"source", "plane"},
                      {"texture", (dir / "card.png").string()},
                      {"scale", {4.0, 1.0, 4.0}},
                      {"position", {0.0, 0.5, 0.0}},
                      {"alpha_cutoff", cutoff}}},
                    {"floor", {{"source", "plane"}, {"scale", {6.0, 1.0, 6.0}}, {"id", 2}}}},
                   "shadow.depth");
    graph["nodes"]["join"]["params"]["light_direction"] = {0.0, -1.0, 0.0};
    graph["nodes"]["shadow"] = {
        {"type", "shadowmap"}, {"params", {{"size", 64}}}, {"inputs", {{"scene", "join.scene"}}}};
    const ImageF depth = render(graph, "shadow.depth");
    // Means over rows through the middle, a few texels either side of the centre column (the
    // card covers the middle of the map; which side is u < 0.5 depends on the light's frame).
    double a = 0, b = 0;
    int n = 0;
    for (int y = depth.height / 2 - 4; y < depth.height / 2 + 4; ++y) {
      for (int k = 4; k < 12; ++k) {
        a += depth.at(depth.width / 2 - k, y, 0);
        b += depth.at(depth.width / 2 + k, y, 0);
        ++n;
      }
    }
    return std::pair{a / n, b / n};
  };
  const auto [opaque_a, opaque_b] = halves(0.0);
  EXPECT_NEAR(opaque_a, opaque_b, 0.01) << "cut-off 0: the whole card casts";
  const auto [cut_a, cut_b] = halves(0.5);
  EXPECT_GT(std::abs(cut_a - cut_b), 0.05) << "the holes must not cast shadows";
}

TEST(Object, EachObjectKeepsItsIdWhenJoined) {
  ImageF id = render(join_graph({{"a",
                                  {{"source", "cube"},
                                   {"position", {-0.6, 0.0, 0.0}},
                                   {"scale", {0.5, 0.5, 0.5}},
                                   {"id", 3}}},
                                 {"b",
                                  {{"source", "sphere"},
                                   {"position", {0.6, 0.0, 0.0}},
                                   {"scale", {0.5, 0.5, 0.5}},
                                   {"id", 7}}}},
                                "gbuf.id"),
                     "gbuf.id");
  std::set<float> seen;
  for (int y = 0; y < id.height; ++y)
    for (int x = 0; x < id.width; ++x) seen.insert(id.at(x, y, 0));
  EXPECT_EQ(seen, (std::set<float>{0.0f, 3.0f, 7.0f}));
}

// Mean image position of the pixels carrying `object`.
glm::dvec2 centroid(const ImageF& id, float object) {
  glm::dvec2 sum(0.0);
  int n = 0;
  for (int y = 0; y < id.height; ++y) {
    for (int x = 0; x < id.width; ++x) {
      if (id.at(x, y, 0) == object) sum += glm::dvec2(x, y), ++n;
    }
  }
  return n > 0 ? sum / static_cast<double>(n) : glm::dvec2(-1.0);
}

TEST(Object, GltfKeyframesMoveTheObject) {
  const std::string lantern = aq::test::source_path("assets/scenes/lantern.gltf");
  nlohmann::json graph =
      join_graph({{"lantern", {{"path", lantern}, {"scale", {0.5, 0.5, 0.5}}}}}, "gbuf.id");
  const glm::dvec2 at_start = centroid(render(graph, "gbuf.id", 1), 1.0f);
  const glm::dvec2 at_one_second = centroid(render(graph, "gbuf.id", 25), 1.0f);  // 24 fps
  ASSERT_GE(at_start.x, 0.0);
  ASSERT_GE(at_one_second.x, 0.0);
  // The file bobs the box up 0.6 (x0.5 scale) at t = 1 s: it rises on screen.
  EXPECT_GT(at_one_second.y, at_start.y + 3.0);
  graph["nodes"]["lantern"]["params"]["animation"] = "none";
  const glm::dvec2 still = centroid(render(graph, "gbuf.id", 25), 1.0f);
  EXPECT_NEAR(still.y, at_start.y, 0.5) << "animation none keeps the rest pose";
}

TEST(Object, SwimLoopsAroundItsPositionWithABodyWave) {
  const std::string fish = aq::test::source_path("assets/scenes/fish.obj");
  nlohmann::json graph = join_graph(
      {{"fish",
        {{"path", fish}, {"animation", "swim"}, {"swim_radius", 0.6}, {"swim_speed", 1.0}}}},
      "gbuf.id");
  std::vector<glm::dvec2> path;
  for (int frame : {1, 13, 25, 37}) path.push_back(centroid(render(graph, "gbuf.id", frame), 1.0f));
  for (const auto& p : path) ASSERT_GE(p.x, 0.0) << "the fish stays in view";
  double travelled = 0;
  for (size_t i = 1; i < path.size(); ++i) travelled += glm::length(path[i] - path[i - 1]);
  EXPECT_GT(travelled, 15.0) << "it swims (pixels along the loop)";
  // The body wave bends the fish: its positions are not those of the rigid mesh moved.
  nlohmann::json glide = graph;
  glide["nodes"]["fish"]["params"]["swim_wave"] = 0.0;
  const ImageF waving = render(graph, "gbuf.id", 7), gliding = render(glide, "gbuf.id", 7);
  int differ = 0;
  for (size_t i = 0; i < waving.pixels.size(); ++i) differ += waving.pixels[i] != gliding.pixels[i];
  EXPECT_GT(differ, 5);
}

TEST(Object, FilesGraphRendersEveryObject) {
  aq::test::RenderOptions options;
  options.width = 160;
  options.height = 90;
  options.output = "gbuf.id";
  auto id = aq::test::render_graph_file(aq::test::source_path("graphs/files.json"), options);
  ASSERT_TRUE(id.ok()) << id.message();
  std::set<float> seen;
  for (int y = 0; y < id->height; ++y)
    for (int x = 0; x < id->width; ++x) seen.insert(id->at(x, y, 0));
  EXPECT_GE(seen.size(), 11u) << "the background and at least ten objects are visible";
  options.output = "";
  auto picture = aq::test::render_graph_file(aq::test::source_path("graphs/files.json"), options);
  ASSERT_TRUE(picture.ok()) << picture.message();
  EXPECT_TRUE(aq::test::all_finite(*picture));
  double lo = 1e9, hi = -1e9;
  for (float v : picture->pixels) lo = std::min<double>(lo, v), hi = std::max<double>(hi, v);
  EXPECT_GT(hi - lo, 0.3) << "not a flat picture";
}

}  // namespace
