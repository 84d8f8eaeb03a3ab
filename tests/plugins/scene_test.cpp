// Tests of the `scene` node and of load-time normal smoothing (aquarelle/sdk/mesh_smoothing.hpp):
// smoothing on a cube, a double-sided plane and a clay pot (unit, finite normals, positions
// untouched, smoother than before), welding by tolerance, and headless renders of the scene
// presets through gbuffer: same seed gives the same image bit for bit, smoothing keeps the
// silhouette, the fish moves while static geometry stays.
#include <aquarelle/sdk/mesh_smoothing.hpp>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <map>
#include <numeric>
#include <random>
#include <set>
#include <string>
#include <vector>

#include "support/harness.h"

// The test process holds the harness's EGL context; the scene node is driven directly through
// its C entry points below, and loads its GL functions (it calls none) from that context.
extern "C" void* eglGetProcAddress(const char* name);

namespace {

using aq::ImageF;

// ---- CPU: meshes built here, independently of the plugin's generators -------------------

struct Mesh {
  std::vector<float> positions, normals;
  std::vector<uint32_t> indices;
  void flat_triangle(const float a[3], const float b[3], const float c[3]) {
    double u[3], v[3];
    for (int k = 0; k < 3; ++k) u[k] = b[k] - a[k], v[k] = c[k] - a[k];
    double n[3] = {u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]};
    double len = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    if (len < 1e-12) return;
    uint32_t base = static_cast<uint32_t>(positions.size() / 3);
    for (const float* p : {a, b, c}) {
      positions.insert(positions.end(), {p[0], p[1], p[2]});
      normals.insert(normals.end(), {static_cast<float>(n[0] / len), static_cast<float>(n[1] / len),
                                     static_cast<float>(n[2] / len)});
    }
    indices.insert(indices.end(), {base, base + 1, base + 2});
  }
  size_t vertex_count() const { return positions.size() / 3; }
};

Mesh flat_cube() {
  Mesh mesh;
  // Each face as two CCW triangles seen from outside.
  const float c[8][3] = {{-.5f, -.5f, -.5f}, {.5f, -.5f, -.5f}, {.5f, .5f, -.5f}, {-.5f, .5f, -.5f},
                         {-.5f, -.5f, .5f},  {.5f, -.5f, .5f},  {.5f, .5f, .5f},  {-.5f, .5f, .5f}};
  const int faces[6][4] = {{0, 3, 2, 1}, {4, 5, 6, 7}, {0, 1, 5, 4},
                           {3, 7, 6, 2}, {0, 4, 7, 3}, {1, 2, 6, 5}};
  for (const auto& f : faces) {
    mesh.flat_triangle(c[f[0]], c[f[1]], c[f[2]]);
    mesh.flat_triangle(c[f[0]], c[f[2]], c[f[3]]);
  }
  return mesh;
}

Mesh double_sided_plane() {
  Mesh mesh;
  const float a[3] = {-1, 0, -1}, b[3] = {-1, 0, 1}, c[3] = {1, 0, 1}, d[3] = {1, 0, -1};
  mesh.flat_triangle(a, b, c);  // +y
  mesh.flat_triangle(a, c, d);
  mesh.flat_triangle(a, c, b);  // the same positions, -y
  mesh.flat_triangle(a, d, c);
  return mesh;
}

// A low-poly pot as a surface of revolution, flat-shaded (the seed's Figure 8 case).
Mesh flat_pot(int segments = 12) {
  const float profile[][2] = {{0.0f, 0.0f}, {0.3f, 0.0f},  {0.5f, 0.3f}, {0.55f, 0.6f},
                              {0.4f, 1.0f}, {0.35f, 1.2f}, {0.3f, 1.2f}, {0.35f, 1.0f},
                              {0.5f, 0.6f}, {0.45f, 0.3f}, {0.0f, 0.1f}};
  const int points = sizeof(profile) / sizeof(profile[0]);
  Mesh mesh;
  auto at = [&](int i, int j, float out[3]) {
    double t = 2.0 * M_PI * (j % segments) / segments;
    out[0] = static_cast<float>(profile[i][0] * std::cos(t));
    out[1] = profile[i][1];
    out[2] = static_cast<float>(profile[i][0] * std::sin(t));
  };
  for (int i = 0; i + 1 < points; ++i) {
    for (int j = 0; j < segments; ++j) {
      float a[3], b[3], c[3], d[3];
      at(i, j, a), at(i + 1, j, b), at(i + 1, j + 1, c), at(i, j + 1, d);
      mesh.flat_triangle(a, b, c);
      mesh.flat_triangle(a, c, d);
    }
  }
  return mesh;
}

void expect_unit_and_finite(const std::vector<float>& normals) {
  for (size_t i = 0; i < normals.size() / 3; ++i) {
    double x = normals[3 * i], y = normals[3 * i + 1], z = normals[3 * i + 2];
    ASSERT_TRUE(std::isfinite(x) && std::isfinite(y) && std::isfinite(z)) << "vertex " << i;
    ASSERT_NEAR(std::sqrt(x * x + y * y + z * z), 1.0, 1e-5) << "vertex " << i;
  }
}

// Largest angle (radians) between normals of vertices at the same position: 0 when smooth.
double largest_seam_angle(const Mesh& mesh, const std::vector<float>& normals) {
  double worst = 0;
  for (size_t i = 0; i < mesh.vertex_count(); ++i) {
    for (size_t j = i + 1; j < mesh.vertex_count(); ++j) {
      double d2 = 0, dot = 0;
      for (int k = 0; k < 3; ++k) {
        double d = mesh.positions[3 * i + k] - mesh.positions[3 * j + k];
        d2 += d * d;
        dot += normals[3 * i + k] * normals[3 * j + k];
      }
      if (d2 < 1e-12) worst = std::max(worst, std::acos(std::clamp(dot, -1.0, 1.0)));
    }
  }
  return worst;
}

TEST(Smoothing, ZeroIterationsLeavesNormalsUntouched) {
  Mesh cube = flat_cube();
  std::vector<float> normals = cube.normals;
  aq::mesh::smooth_normals(cube.positions, cube.indices, normals, {0});
  EXPECT_EQ(normals, cube.normals);
}

TEST(Smoothing, CubeCornersPointAlongTheDiagonalAndPositionsStay) {
  Mesh cube = flat_cube();
  const std::vector<float> positions = cube.positions;
  std::vector<float> normals = cube.normals;
  aq::mesh::smooth_normals(cube.positions, cube.indices, normals, {});
  EXPECT_EQ(cube.positions, positions);  // the silhouette is the input's
  expect_unit_and_finite(normals);
  for (size_t i = 0; i < cube.vertex_count(); ++i) {
    // Every vertex is a corner; by symmetry its smoothed normal is the corner's direction.
    for (int k = 0; k < 3; ++k) {
      double expected = (cube.positions[3 * i + k] > 0 ? 1.0 : -1.0) / std::sqrt(3.0);
      EXPECT_NEAR(normals[3 * i + k], expected, 1e-5) << "vertex " << i;
    }
  }
  EXPECT_LT(largest_seam_angle(cube, normals), 1e-3);  // acos of a float dot near 1
}

TEST(Smoothing, DoubleSidedPlaneKeepsItsFaceNormalsInsteadOfNaN) {
  Mesh plane = double_sided_plane();
  std::vector<float> normals = plane.normals;
  aq::mesh::smooth_normals(plane.positions, plane.indices, normals, {});
  expect_unit_and_finite(normals);
  for (size_t i = 0; i < plane.vertex_count(); ++i) {
    EXPECT_FLOAT_EQ(normals[3 * i + 1], plane.normals[3 * i + 1]) << "vertex " << i;
  }
}

TEST(Smoothing, PotBecomesSmoothAndStaysOutwardWithoutMovingVertices) {
  Mesh pot = flat_pot();
  const std::vector<float> positions = pot.positions;
  EXPECT_GT(largest_seam_angle(pot, pot.normals), 0.3);  // flat-shaded: facets meet at angles
  for (int iterations : {1, 3, 7, 20}) {
    std::vector<float> normals = pot.normals;
    aq::mesh::smooth_normals(pot.positions, pot.indices, normals, {iterations});
    EXPECT_EQ(pot.positions, positions);
    expect_unit_and_finite(normals);
    // Up to the default 7 no normal needed tilting back towards its face: fully smooth. (After
    // 20 the rim's top faces away from the diffused wall normals and gets tilted.)
    if (iterations <= 7) {
      EXPECT_LT(largest_seam_angle(pot, normals), 1e-3) << iterations << " iterations";
    }
    // No vertex ends up lit from behind: its normal stays on its face's side.
    for (size_t i = 0; i < pot.vertex_count(); ++i) {
      double dot = 0;
      for (int k = 0; k < 3; ++k) dot += normals[3 * i + k] * pot.normals[3 * i + k];
      EXPECT_GT(dot, 0.0) << "vertex " << i << " after " << iterations;
    }
  }
}

TEST(Smoothing, MoreIterationsRemoveMoreDetail) {
  // Sum of angles between normals across each triangle: how much shading detail is left.
  Mesh pot = flat_pot(10);
  auto roughness = [&](int iterations) {
    std::vector<float> normals = pot.normals;
    aq::mesh::smooth_normals(pot.positions, pot.indices, normals, {iterations});
    double total = 0;
    for (size_t t = 0; t < pot.indices.size(); t += 3) {
      for (int e = 0; e < 3; ++e) {
        uint32_t a = pot.indices[t + e], b = pot.indices[t + (e + 1) % 3];
        double dot = 0;
        for (int k = 0; k < 3; ++k) dot += normals[3 * a + k] * normals[3 * b + k];
        total += std::acos(std::clamp(dot, -1.0, 1.0));
      }
    }
    return total;
  };
  double r1 = roughness(1), r3 = roughness(3), r7 = roughness(7);
  EXPECT_LT(r3, r1);
  EXPECT_LT(r7, r3);
}

TEST(Smoothing, MissingOrNaNNormalsFallBackToFaceNormals) {
  Mesh cube = flat_cube();
  std::vector<float> none;
  aq::mesh::smooth_normals(cube.positions, cube.indices, none, {});
  ASSERT_EQ(none.size(), cube.positions.size());
  expect_unit_and_finite(none);
  std::vector<float> broken = cube.normals;
  for (float& v : broken) v = std::nanf("");
  aq::mesh::smooth_normals(cube.positions, cube.indices, broken, {});
  expect_unit_and_finite(broken);
}

TEST(Weld, UsesDistanceNotRoundedCells) {
  // Two copies of a point straddling a cell boundary (rounding would split them), a third
  // chained to the second, and a fourth just outside the tolerance.
  const double tol = 1e-4;
  std::vector<float> positions = {0.99995f, 0, 0, 1.00004f, 0, 0, 1.00012f, 0, 0, 1.00030f, 0, 0};
  uint32_t groups = 0;
  std::vector<uint32_t> group = aq::mesh::weld_positions(positions, tol, &groups);
  EXPECT_EQ(group[0], group[1]);
  EXPECT_EQ(group[1], group[2]);  // transitive
  EXPECT_NE(group[2], group[3]);
  EXPECT_EQ(groups, 2u);
}

// The definition the weld implements, by brute force: vertices closer than `tol`,
// transitively, share a group. Returns a canonical labelling (first vertex of each group).
std::vector<uint32_t> weld_by_definition(const std::vector<float>& p, double tol) {
  const size_t n = p.size() / 3;
  std::vector<uint32_t> label(n);
  std::iota(label.begin(), label.end(), 0u);
  std::function<uint32_t(uint32_t)> find = [&](uint32_t x) {
    return label[x] == x ? x : label[x] = find(label[x]);
  };
  for (size_t i = 0; i < n; ++i)
    for (size_t j = 0; j < i; ++j) {
      const double dx = p[3 * i] - p[3 * j], dy = p[3 * i + 1] - p[3 * j + 1],
                   dz = p[3 * i + 2] - p[3 * j + 2];
      if (std::sqrt(dx * dx + dy * dy + dz * dz) <= tol) {
        const uint32_t a = find(i), b = find(j);
        label[std::max(a, b)] = std::min(a, b);
      }
    }
  for (size_t i = 0; i < n; ++i) label[i] = find(i);
  return label;
}

// Two labellings describe the same partition.
bool same_partition(const std::vector<uint32_t>& a, const std::vector<uint32_t>& b) {
  std::map<uint32_t, uint32_t> a_to_b, b_to_a;
  for (size_t i = 0; i < a.size(); ++i) {
    if (a_to_b.emplace(a[i], b[i]).first->second != b[i]) return false;
    if (b_to_a.emplace(b[i], a[i]).first->second != a[i]) return false;
  }
  return true;
}

std::vector<float> random_cloud(size_t n, double extent, uint32_t seed) {
  std::mt19937 random(seed);
  std::uniform_real_distribution<float> coordinate(0.0f, static_cast<float>(extent));
  std::vector<float> p(3 * n);
  for (float& v : p) v = coordinate(random);
  return p;
}

TEST(Weld, MatchesTheDistanceDefinitionOnRandomClouds) {
  // Sparse to dense: from isolated points to chains of welds across many cells.
  const double tol = 0.01;
  for (const double extent : {1.0, 0.3, 0.12}) {
    const std::vector<float> p = random_cloud(1500, extent, 11);
    uint32_t groups = 0;
    const std::vector<uint32_t> group = aq::mesh::weld_positions(p, tol, &groups);
    EXPECT_TRUE(same_partition(group, weld_by_definition(p, tol))) << "extent " << extent;
  }
}

// 200,000 distinct vertices inside one tolerance-sized cube (a file can hold them: the weld
// tolerance is relative to the whole mesh's size, which one far vertex makes large). Every
// vertex compared against every earlier one in its cell: 2e10 distances, minutes (issue 40).
// By the definition they are all one group.
TEST(Weld, ACrowdOfDistinctVerticesInOneCellIsWeldedInLinearTime) {
  const double tol = 1e-2;
  std::vector<float> p = random_cloud(200000, tol / 2, 5);
  uint32_t groups = 0;
  aq::mesh::weld_positions(p, tol, &groups);
  EXPECT_EQ(groups, 1u);
}

// Where a crowd is not all within reach, the guarantee still holds: every two vertices within
// the tolerance share a group; welded vertices further apart than (1 + sqrt 3) tolerance are
// only ever joined through a chain of such steps.
TEST(Weld, InsideACrowdVerticesWithinTheToleranceAlwaysShareAGroup) {
  const double tol = 1e-2;
  const std::vector<float> p = random_cloud(3000, 3 * tol, 9);
  uint32_t groups = 0;
  const std::vector<uint32_t> group = aq::mesh::weld_positions(p, tol, &groups);
  const std::vector<uint32_t> exact = weld_by_definition(p, tol);
  for (size_t i = 0; i < exact.size(); ++i)
    ASSERT_EQ(group[i], group[exact[i]]) << "vertex " << i << " within reach of " << exact[i];
  const std::vector<uint32_t> loose = weld_by_definition(p, (1 + std::sqrt(3.0)) * tol);
  for (size_t i = 0; i < group.size(); ++i)
    for (size_t j = 0; j < i; ++j)
      if (group[i] == group[j]) {
        ASSERT_EQ(loose[i], loose[j]) << i << " and " << j;
      }
}

// ---- GPU: the scene node through gbuffer -------------------------------------------------

std::string scene_graph(const std::string& scene_id, const nlohmann::json& scene_params) {
  nlohmann::json graph = {
      {"aquarelle", 1},
      {"settings", {{"width", 96}, {"height", 64}}},
      {"nodes",
       {{scene_id, {{"type", "scene"}, {"params", scene_params}}},
        {"gbuf", {{"type", "gbuffer"}, {"inputs", {{"scene", scene_id + ".scene"}}}}}}},
      {"output", "gbuf.albedo"}};
  return graph.dump();
}

ImageF render(const std::string& graph, const std::string& output, int frame = 1) {
  aq::test::RenderOptions options;
  options.width = 96;
  options.height = 64;
  options.output = output;
  options.frame = frame;
  auto image = aq::test::render_graph(graph, options);
  EXPECT_TRUE(image.ok()) << (image.ok() ? "" : image.message());
  return image.ok() ? *image : ImageF();
}

TEST(SceneNode, SameSeedGivesTheSameImageBitForBit) {
  const nlohmann::json params = {{"preset", "underwater"}, {"seed", 7}};
  for (const char* port : {"albedo", "normal", "id"}) {
    ImageF a = render(scene_graph("scene_a", params), std::string("gbuf.") + port);
    ImageF b = render(scene_graph("scene_b", params), std::string("gbuf.") + port);
    ASSERT_FALSE(a.empty());
    EXPECT_EQ(a.pixels, b.pixels) << port;
  }
  ImageF other =
      render(scene_graph("scene_c", {{"preset", "underwater"}, {"seed", 8}}), "gbuf.albedo");
  ImageF seven = render(scene_graph("scene_d", params), "gbuf.albedo");
  EXPECT_GT(aq::test::max_abs_diff(other, seven), 0.05) << "another seed, another scene";
}

TEST(SceneNode, UnderwaterHasManyObjectsAndFiniteNormals) {
  ImageF id = render(scene_graph("scene", {{"preset", "underwater"}}), "gbuf.id");
  ImageF normal = render(scene_graph("scene", {{"preset", "underwater"}}), "gbuf.normal");
  ASSERT_FALSE(id.empty());
  std::set<int> ids;
  for (int y = 0; y < id.height; ++y)
    for (int x = 0; x < id.width; ++x) ids.insert(static_cast<int>(std::lround(id.at(x, y, 0))));
  EXPECT_GE(ids.size(), 8u) << "sand, pots, rocks, corals, seaweed, fish... should be in view";
  EXPECT_TRUE(aq::test::all_finite(normal));
}

TEST(SceneNode, SmoothingKeepsTheSilhouette) {
  const nlohmann::json view = {{"camera_position", {1.8, 1.6, 2.4}},
                               {"camera_target", {0, 0.6, 0}}};
  for (const char* preset : {"pot", "cube", "double_plane"}) {
    nlohmann::json flat = view, smooth = view;
    flat["preset"] = smooth["preset"] = preset;
    flat["smoothing"] = 0;
    smooth["smoothing"] = 7;
    ImageF id_flat = render(scene_graph("flat", flat), "gbuf.id");
    ImageF id_smooth = render(scene_graph("smooth", smooth), "gbuf.id");
    ASSERT_FALSE(id_flat.empty());
    EXPECT_EQ(id_flat.pixels, id_smooth.pixels) << preset;
    ImageF n_flat = render(scene_graph("flat", flat), "gbuf.normal");
    ImageF n_smooth = render(scene_graph("smooth", smooth), "gbuf.normal");
    EXPECT_TRUE(aq::test::all_finite(n_smooth)) << preset;
    if (std::string(preset) != "double_plane") {
      EXPECT_GT(aq::test::max_abs_diff(n_flat, n_smooth), 0.1) << preset << ": normals changed";
    } else {
      EXPECT_EQ(n_flat.pixels, n_smooth.pixels) << "a double-sided plane keeps its face normals";
    }
  }
}

TEST(SceneNode, TheFishSwimsAndTheRestStaysStill) {
  const std::string graph = scene_graph("scene", {{"preset", "underwater"}});
  ImageF first = render(graph, "gbuf.id", 1);
  ImageF later = render(graph, "gbuf.id", 25);
  ASSERT_FALSE(first.empty());
  // Count pixels that changed: some (fish, seaweed), but far from all.
  int changed = 0;
  for (int y = 0; y < first.height; ++y)
    for (int x = 0; x < first.width; ++x) changed += first.at(x, y, 0) != later.at(x, y, 0);
  EXPECT_GT(changed, 5);
  EXPECT_LT(changed, first.width * first.height / 4);
}

// ---- The scene node through its C ABI, with a host that records what it publishes ---------

struct RecordingHost {
  aq_host host{};
  const aq_scene* scene = nullptr;
  std::string error;
};

RecordingHost* recording(void* host_data) {
  return static_cast<RecordingHost*>(host_data);
}

class DirectSceneNode {
 public:
  DirectSceneNode() {
    // A real render first, so the harness's GL context is current on this thread.
    render(scene_graph("warm_up", {{"preset", "cube"}}), "gbuf.id");
    type_ = aq::test::registry().find("scene");
    if (type_ == nullptr || type_->desc == nullptr) return;
    recorder_.host.abi_version = AQ_ABI_VERSION;
    recorder_.host.struct_size = sizeof(aq_host);
    recorder_.host.get_proc_address = [](const char* name) { return eglGetProcAddress(name); };
    recorder_.host.fail = [](void* data, const char* message) { recording(data)->error = message; };
    recorder_.host.log = [](void*, int, const char*) {};
    recorder_.host.output_scene = [](void* data, uint32_t, const aq_scene* scene) {
      recording(data)->scene = scene;
      return static_cast<int>(AQ_OK);
    };
    for (const aq::ParamInfo& p : type_->params) {
      aq_param_value value{};
      for (int k = 0; k < 3; ++k) value.f[k] = p.default_value[k];
      value.i = static_cast<int64_t>(p.default_value[0]);
      strings_.push_back(p.default_string);
      params_.push_back(value);
    }
    for (size_t i = 0; i < params_.size(); ++i) params_[i].s = strings_[i].c_str();
    instance_ = type_->desc->create(&recorder_.host);
  }
  ~DirectSceneNode() {
    if (instance_ != nullptr) type_->desc->destroy(instance_);
  }
  bool ready() const { return instance_ != nullptr; }
  aq_param_value& param(const std::string& name) {
    return params_[static_cast<size_t>(type_->param_index(name))];
  }
  const aq_scene* run(double time) {
    aq_process_ctx ctx{};
    ctx.struct_size = sizeof(ctx);
    ctx.host = &recorder_.host;
    ctx.host_data = &recorder_;
    ctx.node_id = "scene";
    ctx.params = params_.data();
    ctx.param_count = static_cast<uint32_t>(params_.size());
    ctx.width = ctx.height = 64;
    ctx.time = time;
    ctx.fps = 24;
    ctx.gl_generation = 0x5CE9Eu;
    recorder_.scene = nullptr;
    int status = type_->desc->process(instance_, &ctx);
    EXPECT_EQ(status, AQ_OK) << recorder_.error;
    return recorder_.scene;
  }

 private:
  const aq::NodeType* type_ = nullptr;
  RecordingHost recorder_;
  std::vector<aq_param_value> params_;
  std::vector<std::string> strings_;
  void* instance_ = nullptr;
};

std::vector<uint64_t> revisions(const aq_scene* scene) {
  std::vector<uint64_t> out;
  for (uint32_t i = 0; i < scene->mesh_count; ++i)
    out.push_back(scene->meshes[i].geometry_revision);
  return out;
}

TEST(SceneData, RevisionsChangeOnlyWithVertexData) {
  DirectSceneNode node;
  ASSERT_TRUE(node.ready());
  const aq_scene* scene = node.run(0.0);
  ASSERT_NE(scene, nullptr);
  ASSERT_GT(scene->mesh_count, 10u);
  const std::vector<uint64_t> first = revisions(scene);
  EXPECT_EQ(std::set<uint64_t>(first.begin(), first.end()).size(), first.size()) << "unique";

  EXPECT_EQ(revisions(node.run(0.0)), first) << "same time, same data";

  node.param("camera_position").f[0] = 3.0;
  node.param("light_direction").f[2] = 0.5;
  EXPECT_EQ(revisions(node.run(0.0)), first) << "camera and light touch no geometry";

  scene = node.run(1.5);
  const std::vector<uint64_t> later = revisions(scene);
  ASSERT_EQ(later.size(), first.size());
  int changed = 0;
  for (size_t i = 0; i < first.size(); ++i) changed += later[i] != first[i];
  // Only the animated objects (seaweed clusters and the fish, published last) changed.
  EXPECT_GE(changed, 2);
  EXPECT_LE(changed, 8);
  for (size_t i = 0; i < first.size() - static_cast<size_t>(changed); ++i) {
    EXPECT_EQ(later[i], first[i]) << "static mesh " << i;
  }

  node.param("seed").i = 8;
  const std::vector<uint64_t> reseeded = revisions(node.run(1.5));
  for (size_t i = 0; i < std::min(reseeded.size(), later.size()); ++i) {
    EXPECT_NE(reseeded[i], later[i]) << "a new seed is new geometry";
  }
}

TEST(SceneData, BoundsHoldEveryVertexAtEveryTimeAndStayPut) {
  DirectSceneNode node;
  ASSERT_TRUE(node.ready());
  float first_min[3] = {0, 0, 0}, first_max[3] = {0, 0, 0};
  for (double time : {0.0, 2.0, 5.5, 11.0, 17.0}) {
    const aq_scene* scene = node.run(time);
    ASSERT_NE(scene, nullptr);
    if (time == 0.0) {
      std::copy(scene->bounds_min, scene->bounds_min + 3, first_min);
      std::copy(scene->bounds_max, scene->bounds_max + 3, first_max);
    }
    for (int k = 0; k < 3; ++k) {
      EXPECT_EQ(scene->bounds_min[k], first_min[k]) << "bounds move with time";
      EXPECT_EQ(scene->bounds_max[k], first_max[k]) << "bounds move with time";
    }
    for (uint32_t m = 0; m < scene->mesh_count; ++m) {
      const aq_mesh& mesh = scene->meshes[m];
      for (uint32_t v = 0; v < mesh.vertex_count; ++v) {
        double p[3];
        for (int r = 0; r < 3; ++r) {
          p[r] = mesh.model[12 + r];
          for (int c = 0; c < 3; ++c) p[r] += mesh.model[4 * c + r] * mesh.positions[3 * v + c];
        }
        for (int k = 0; k < 3; ++k) {
          ASSERT_GE(p[k], scene->bounds_min[k] - 1e-4) << "mesh " << m << " t " << time;
          ASSERT_LE(p[k], scene->bounds_max[k] + 1e-4) << "mesh " << m << " t " << time;
        }
        for (int k = 0; k < 3; ++k) ASSERT_TRUE(std::isfinite(mesh.normals[3 * v + k]));
      }
    }
  }
}

TEST(SceneData, SameSeedSameVerticesInTwoInstances) {
  DirectSceneNode a, b;
  ASSERT_TRUE(a.ready() && b.ready());
  const aq_scene* sa = a.run(3.25);
  const aq_scene* sb = b.run(3.25);
  ASSERT_EQ(sa->mesh_count, sb->mesh_count);
  for (uint32_t m = 0; m < sa->mesh_count; ++m) {
    const aq_mesh &ma = sa->meshes[m], &mb = sb->meshes[m];
    ASSERT_EQ(ma.vertex_count, mb.vertex_count);
    EXPECT_EQ(ma.object_id, mb.object_id);
    EXPECT_EQ(0, std::memcmp(ma.positions, mb.positions, 12u * ma.vertex_count)) << m;
    EXPECT_EQ(0, std::memcmp(ma.normals, mb.normals, 12u * ma.vertex_count)) << m;
    EXPECT_EQ(0, std::memcmp(ma.colors, mb.colors, 12u * ma.vertex_count)) << m;
  }
}

TEST(SceneNode, LoadsAnObjFileWithItsMaterialColour) {
  const std::filesystem::path dir = std::filesystem::temp_directory_path() / "aq_scene_test";
  std::filesystem::create_directories(dir);
  {
    std::ofstream mtl(dir / "box.mtl");
    mtl << "newmtl red\nKd 0.8 0.2 0.1\n";
    std::ofstream obj(dir / "box.obj");
    obj << "mtllib box.mtl\nusemtl red\n"
           "v -0.5 -0.5 -0.5\nv 0.5 -0.5 -0.5\nv 0.5 0.5 -0.5\nv -0.5 0.5 -0.5\n"
           "v -0.5 -0.5 0.5\nv 0.5 -0.5 0.5\nv 0.5 0.5 0.5\nv -0.5 0.5 0.5\n"
           "f 1 4 3 2\nf 5 6 7 8\nf 1 2 6 5\nf 4 8 7 3\nf 1 5 8 4\nf 2 3 7 6\n";
  }
  const nlohmann::json params = {{"preset", "file"},
                                 {"path", (dir / "box.obj").string()},
                                 {"camera_position", {1.6, 1.2, 2.2}},
                                 {"camera_target", {0, 0, 0}}};
  ImageF id = render(scene_graph("file_scene", params), "gbuf.id");
  ImageF albedo = render(scene_graph("file_scene", params), "gbuf.albedo");
  ImageF normal = render(scene_graph("file_scene", params), "gbuf.normal");
  ImageF cube = render(scene_graph("cube_scene", {{"preset", "cube"},
                                                  {"camera_position", {1.6, 1.2, 2.2}},
                                                  {"camera_target", {0, 0, 0}}}),
                       "gbuf.id");
  ASSERT_FALSE(id.empty());
  EXPECT_EQ(id.pixels, cube.pixels) << "the same cube, from a file, covers the same pixels";
  EXPECT_NEAR(albedo.at(48, 32, 0), 0.8, 1e-6);
  EXPECT_NEAR(albedo.at(48, 32, 1), 0.2, 1e-6);
  EXPECT_NEAR(albedo.at(48, 32, 2), 0.1, 1e-6);
  EXPECT_TRUE(aq::test::all_finite(normal));
}

TEST(SceneNode, MissingFileIsAClearError) {
  aq::test::RenderOptions options;
  options.output = "gbuf.albedo";
  auto image = aq::test::render_graph(
      scene_graph("scene", {{"preset", "file"}, {"path", "/nonexistent/model.obj"}}), options);
  ASSERT_FALSE(image.ok());
  EXPECT_NE(image.message().find("model.obj"), std::string::npos) << image.message();
}

}  // namespace
