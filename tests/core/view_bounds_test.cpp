// What the camera sees, as geometry (view_bounds.hpp), and the shadow window fitted to it
// (scene_math.hpp): the clipped polytope's extremes agree with brute-force sampling of the box,
// boxes in, out of and across the frustum, the water plane, and the view-fitted light matrix:
// every receiver in view inside it, finer texels than the scene fit, texels that keep their
// place in the world while the camera moves, and the fallback when nothing is in view.
#include <gtest/gtest.h>

#include <aquarelle/sdk/scene_math.hpp>
#include <aquarelle/sdk/view_bounds.hpp>

#include <array>
#include <cmath>
#include <cstring>
#include <random>
#include <vector>

namespace {

using aq::view_bounds::Box;
using aq::view_bounds::Plane;
using aq::view_bounds::signed_distance;

aq_camera camera_at(glm::vec3 position, glm::vec3 target, float fov = 50.0f) {
  aq_camera camera{};
  for (int k = 0; k < 3; ++k) {
    camera.position[k] = position[k];
    camera.target[k] = target[k];
  }
  camera.up[1] = 1.0f;
  camera.fov_y_degrees = fov;
  camera.near_plane = 0.05f;
  camera.far_plane = 200.0f;
  return camera;
}

glm::dmat4 view_of(const aq_camera& camera) {
  return glm::dmat4(aq::scene_math::camera_view(camera));
}

std::array<Plane, 6> frustum_of(const aq_camera& camera, float aspect) {
  return aq::view_bounds::frustum_planes(aq::scene_math::camera_view_projection(camera, aspect));
}

Box box_of(glm::dvec3 lo, glm::dvec3 hi) {
  Box box;
  box.add(lo);
  box.add(hi);
  return box;
}

// The nearest camera depth over a dense grid of the box's points inside the planes: an upper
// bound of the true minimum that converges to it, computed without any clipping.
double sampled_nearest_depth(const Box& box, std::span<const Plane> planes, const glm::dmat4& view,
                             int n) {
  double nearest = 1e300;
  for (int i = 0; i <= n; ++i)
    for (int j = 0; j <= n; ++j)
      for (int k = 0; k <= n; ++k) {
        const glm::dvec3 t(double(i) / n, double(j) / n, double(k) / n);
        const glm::dvec3 p = box.lo + t * (box.hi - box.lo);
        bool inside = true;
        for (const Plane& plane : planes) inside = inside && signed_distance(plane, p) >= 0.0;
        if (inside) nearest = std::min(nearest, -(view * glm::dvec4(p, 1.0)).z);
      }
  return nearest;
}

TEST(ViewBounds, BoxInsideTheFrustumKeepsItsCorners) {
  const aq_camera camera = camera_at({0, 0, 10}, {0, 0, 0});
  const auto points =
      aq::view_bounds::clip_box(box_of({-1, -1, -1}, {1, 1, 1}), frustum_of(camera, 1.0f));
  ASSERT_FALSE(points.empty());
  for (const auto& p : points) {
    EXPECT_NEAR(std::abs(p.x), 1.0, 1e-9);
    EXPECT_NEAR(std::abs(p.y), 1.0, 1e-9);
    EXPECT_NEAR(std::abs(p.z), 1.0, 1e-9);
  }
  EXPECT_NEAR(*aq::view_bounds::nearest_depth(points, view_of(camera)), 9.0, 1e-9);
}

TEST(ViewBounds, BoxesBehindOrBesideTheCameraAreNotSeen) {
  const aq_camera camera = camera_at({0, 0, 10}, {0, 0, 0});  // fov 50, looking down -z
  const auto frustum = frustum_of(camera, 1.0f);
  EXPECT_TRUE(aq::view_bounds::clip_box(box_of({-1, -1, 11}, {1, 1, 13}), frustum).empty());
  // Beside: at depth 6 (the boxes' far side) the view reaches x = 6 tan(25°) ≈ 2.8, so a box
  // from x = 3 is outside and one from x = 2 reaches in.
  EXPECT_TRUE(aq::view_bounds::clip_box(box_of({3, -1, 4}, {4, 1, 6}), frustum).empty());
  EXPECT_FALSE(aq::view_bounds::clip_box(box_of({2, -1, 4}, {4, 1, 6}), frustum).empty());
}

TEST(ViewBounds, CameraInsideABoxSeesItFromTheNearPlane) {
  const aq_camera camera = camera_at({0, 0, 0}, {0, 0, -1});
  const auto points =
      aq::view_bounds::clip_box(box_of({-3, -3, -3}, {3, 3, 3}), frustum_of(camera, 1.5f));
  EXPECT_NEAR(*aq::view_bounds::nearest_depth(points, view_of(camera)), camera.near_plane, 1e-6);
}

// A floor seen from above at a slant: the nearest point is where the frustum's bottom plane
// meets the floor's top, on no corner of the box; sampling the box agrees.
TEST(ViewBounds, NearestDepthMatchesSamplingForRandomViews) {
  std::mt19937 random(11);
  std::uniform_real_distribution<float> u(-1.0f, 1.0f);
  int seen = 0;
  for (int trial = 0; trial < 40; ++trial) {
    const aq_camera camera =
        camera_at({3.0f * u(random), 2.5f + 2.0f * u(random), 6.0f},
                  {u(random), 0.5f * u(random), -1.0f}, 40.0f + 10 * u(random));
    std::vector<Plane> planes;
    for (const Plane& p : frustum_of(camera, 16.0f / 9.0f)) planes.push_back(p);
    planes.push_back(aq::view_bounds::below(0.2 + 0.3 * u(random)));
    const Box floor = box_of({-8, -0.5, -8}, {8, 0.6, 8});
    const auto points = aq::view_bounds::clip_box(floor, planes);
    const double sampled = sampled_nearest_depth(floor, planes, view_of(camera), 96);
    if (points.empty()) {
      EXPECT_GT(sampled, 1e299) << "trial " << trial;  // sampling finds nothing either
      continue;
    }
    ++seen;
    const double nearest = *aq::view_bounds::nearest_depth(points, view_of(camera));
    // Exact minimum <= any sample; the grid (1/96 of the box) bounds how far above it lies.
    EXPECT_LE(nearest, sampled + 1e-9) << "trial " << trial;
    EXPECT_GE(nearest, sampled - 0.25) << "trial " << trial;
    for (const auto& p : points) {
      for (const Plane& plane : planes) {
        EXPECT_GE(signed_distance(plane, p), -1e-6 * glm::length(glm::dvec3(plane)));
      }
    }
  }
  EXPECT_GT(seen, 20);
}

TEST(ViewBounds, PixelsPerWorldUnitFollowsThePinholeModel) {
  // fov 90: the half height of the view at depth d is d, so H rows show 2d world units.
  EXPECT_NEAR(aq::view_bounds::pixels_per_world_unit(90.0, 200, 5.0), 200.0 / 10.0, 1e-9);
  EXPECT_NEAR(aq::view_bounds::pixels_per_world_unit(90.0, 200, 10.0), 10.0, 1e-9);
}

// A scene with one mesh: a box with the given world corners (8 vertices, no triangles needed).
struct BoxScene {
  std::array<float, 24> positions{};
  aq_mesh mesh{};
  aq_scene scene{};
  BoxScene(glm::vec3 lo, glm::vec3 hi, const aq_camera& camera) {
    for (int c = 0; c < 8; ++c) {
      positions[3 * c + 0] = (c & 1) ? hi.x : lo.x;
      positions[3 * c + 1] = (c & 2) ? hi.y : lo.y;
      positions[3 * c + 2] = (c & 4) ? hi.z : lo.z;
    }
    mesh.positions = positions.data();
    mesh.vertex_count = 8;
    for (int i = 0; i < 4; ++i) mesh.model[5 * i] = 1.0f;
    mesh.object_id = 1;
    mesh.geometry_revision = 42;
    scene.struct_size = sizeof(aq_scene);
    scene.meshes = &mesh;
    scene.mesh_count = 1;
    scene.camera = camera;
    scene.light.direction[0] = 0.3f;
    scene.light.direction[1] = -1.0f;
    scene.light.direction[2] = 0.1f;
    for (int k = 0; k < 3; ++k) {
      scene.bounds_min[k] = lo[k];
      scene.bounds_max[k] = hi[k];
    }
    scene.water_height = 10.0f;
  }
};

glm::dvec3 to_clip(const glm::mat4& m, const glm::dvec3& p) {
  const glm::dvec4 c = glm::dmat4(m) * glm::dvec4(p, 1.0);
  return glm::dvec3(c) / c.w;
}

TEST(ShadowFit, ReceiversInViewAreInsideAndTexelsAreFiner) {
  // Looking steeply down at a 40 x 40 floor: the camera sees a few units of it.
  const aq_camera camera = camera_at({0.0f, 3.0f, 2.0f}, {0.0f, 0.0f, 0.5f});
  BoxScene s({-20, -0.5f, -20}, {20, 0.5f, 20}, camera);
  aq::view_bounds::MeshBoxes boxes;
  const float aspect = 16.0f / 9.0f;
  const auto fit = aq::scene_math::fit_to_view(s.scene, boxes.world_boxes(s.scene), aspect);
  ASSERT_TRUE(fit.any_visible);
  const int size = 512;
  const glm::mat4 fitted = aq::scene_math::light_view_projection(s.scene, fit, size);
  const glm::mat4 whole = aq::scene_math::light_view_projection(s.scene);
  // Every point of the floor in view lands inside the fitted map.
  const auto planes = frustum_of(camera, aspect);
  const Box floor = box_of({-20, -0.5, -20}, {20, 0.5, 20});
  for (const auto& p : aq::view_bounds::clip_box(floor, planes)) {
    const glm::dvec3 c = to_clip(fitted, p);
    EXPECT_LE(std::abs(c.x), 1.0 + 1e-6);
    EXPECT_LE(std::abs(c.y), 1.0 + 1e-6);
    EXPECT_LE(std::abs(c.z), 1.0 + 1e-6);
  }
  // The whole scene's depth range is kept: a caster anywhere in the bounds is not clipped.
  for (int corner = 0; corner < 8; ++corner) {
    EXPECT_LE(std::abs(to_clip(fitted, floor.corner(corner)).z), 1.0 + 1e-6);
  }
  // World units per texel shrink by more than 3.
  const double fitted_scale = glm::length(glm::dvec3(fitted[0][0], fitted[1][0], fitted[2][0]));
  const double whole_scale = glm::length(glm::dvec3(whole[0][0], whole[1][0], whole[2][0]));
  EXPECT_GT(fitted_scale, 3.0 * whole_scale);
  // Computed twice from the same inputs (shadowmap and cel_light do): bit-identical.
  aq::view_bounds::MeshBoxes other;
  const auto again = aq::scene_math::fit_to_view(s.scene, other.world_boxes(s.scene), aspect);
  const glm::mat4 twice = aq::scene_math::light_view_projection(s.scene, again, size);
  EXPECT_EQ(0, std::memcmp(&fitted, &twice, sizeof(glm::mat4)));
}

// Moving the camera a little moves the window by whole texels: a fixed world point keeps its
// position within a texel, so shadow edges do not crawl.
TEST(ShadowFit, TexelsKeepTheirPlaceAsTheCameraMoves) {
  const int size = 256;
  const glm::dvec3 probe(0.37, 0.1, -1.23);
  double first_fraction = -1.0;
  glm::mat4 first;
  int moved = 0;
  for (int step = 0; step < 6; ++step) {
    const float dx = 0.07f * static_cast<float>(step);
    const aq_camera camera = camera_at({dx, 3.0f, 2.0f}, {dx, 0.0f, 0.5f});
    BoxScene s({-20, -0.5f, -20}, {20, 0.5f, 20}, camera);
    aq::view_bounds::MeshBoxes boxes;
    const auto fit = aq::scene_math::fit_to_view(s.scene, boxes.world_boxes(s.scene), 1.5f);
    const glm::mat4 m = aq::scene_math::light_view_projection(s.scene, fit, size);
    const glm::dvec3 c = to_clip(m, probe);
    const double texel = (c.x * 0.5 + 0.5) * size;
    const double fraction = texel - std::floor(texel);
    if (step == 0) {
      first_fraction = fraction;
      first = m;
    } else {
      if (std::memcmp(&first, &m, sizeof(glm::mat4)) != 0) ++moved;
      EXPECT_NEAR(fraction, first_fraction, 1e-3) << "step " << step;
    }
  }
  EXPECT_GT(moved, 0) << "the window never moved: the test shows nothing";
}

TEST(ShadowFit, NothingInViewFallsBackToTheSceneFit) {
  const aq_camera camera = camera_at({0, 50, 0}, {0, 100, 0.1f});  // looking up, away
  BoxScene s({-2, -0.5f, -2}, {2, 0.5f, 2}, camera);
  aq::view_bounds::MeshBoxes boxes;
  const auto fit = aq::scene_math::fit_to_view(s.scene, boxes.world_boxes(s.scene), 1.0f);
  EXPECT_FALSE(fit.any_visible);
  const glm::mat4 a = aq::scene_math::light_view_projection(s.scene, fit, 512);
  const glm::mat4 b = aq::scene_math::light_view_projection(s.scene);
  EXPECT_EQ(0, std::memcmp(&a, &b, sizeof(glm::mat4)));
  EXPECT_EQ(aq::scene_math::shadow_size_for_view(fit, camera, 720, 1024), 1024);
}

TEST(ShadowFit, SizeGivesATexelPerPixelAtTheNearestReceiver) {
  // Looking straight down at a 4 x 4 slab from 10 above its top, fov 90: the slab spans about
  // 4 units of light space, a unit covers 720 / 20 = 36 pixels at depth 10.
  const aq_camera camera = camera_at({0, 10.5f, 0}, {0, 0, 0}, 90.0f);
  BoxScene s({-2, -0.5f, -2}, {2, 0.5f, 2}, camera);
  aq::view_bounds::MeshBoxes boxes;
  const auto fit = aq::scene_math::fit_to_view(s.scene, boxes.world_boxes(s.scene), 1.0f);
  ASSERT_TRUE(fit.any_visible);
  EXPECT_NEAR(fit.nearest_depth, 10.0, 1e-4);
  const double extent = std::max(fit.hi.x - fit.lo.x, fit.hi.y - fit.lo.y);
  const int expected = static_cast<int>(std::ceil(extent * 36.0 / 16.0) * 16.0);
  EXPECT_EQ(aq::scene_math::shadow_size_for_view(fit, camera, 720, 8192), expected);
  EXPECT_EQ(aq::scene_math::shadow_size_for_view(fit, camera, 720, 64), 64);  // the cap
}

}  // namespace

// Two thin blades two units apart in one mesh (the flagship's seaweed cluster): each chunk's box
// holds every corner of its triangles, moved by the mesh's model matrix; together they cover far
// less than the mesh's one box, which spans the gap; bad indices and non-finite corners are
// skipped, and a mesh without indices has no chunks (its box is used instead).
TEST(TriangleChunkBoxes, EachChunkHoldsItsTrianglesAndTheGapIsLeftOut) {
  std::vector<float> positions;
  std::vector<uint32_t> indices;
  for (int blade = 0; blade < 2; ++blade) {
    const float x = 2.0f * static_cast<float>(blade);
    for (int k = 0; k <= 8; ++k) {  // a strip of 16 triangles up to y = 2
      const float y = 0.25f * static_cast<float>(k);
      positions.insert(positions.end(), {x, y, 0.0f, x + 0.1f, y, 0.0f});
    }
    const uint32_t base = static_cast<uint32_t>(blade) * 18;
    for (uint32_t k = 0; k < 8; ++k) {
      const uint32_t a = base + 2 * k;
      indices.insert(indices.end(), {a, a + 1, a + 2, a + 1, a + 3, a + 2});
    }
  }
  indices.insert(indices.end(), {0, 1, 999});  // an index past the vertices: skipped
  aq_mesh mesh{};
  mesh.positions = positions.data();
  mesh.indices = indices.data();
  mesh.vertex_count = static_cast<uint32_t>(positions.size() / 3);
  mesh.index_count = static_cast<uint32_t>(indices.size());
  const glm::dvec3 offset(5.0, -1.0, 3.0);
  for (int c = 0; c < 16; ++c) mesh.model[c] = (c % 5 == 0) ? 1.0f : 0.0f;
  mesh.model[12] = 5.0f;
  mesh.model[13] = -1.0f;
  mesh.model[14] = 3.0f;

  const std::vector<Box> chunks = aq::view_bounds::triangle_chunk_boxes(mesh, 4);
  ASSERT_EQ(chunks.size(), 9u);  // 33 triangles: eight chunks of four and the last one
  for (size_t t = 0; t + 3 <= indices.size(); t += 3) {
    const Box& box = chunks[t / 12];
    for (size_t k = t; k < t + 3; ++k) {
      if (indices[k] >= mesh.vertex_count) continue;
      const glm::dvec3 p = glm::dvec3(positions[3 * indices[k]], positions[3 * indices[k] + 1],
                                      positions[3 * indices[k] + 2]) +
                           offset;
      EXPECT_TRUE(glm::all(glm::greaterThanEqual(p, box.lo)) &&
                  glm::all(glm::lessThanEqual(p, box.hi)))
          << "triangle " << t / 3 << " corner outside its chunk's box";
    }
  }
  double area = 0.0;  // the chunks' x-y extent, against the mesh box's 2.1 x 2
  for (const Box& box : chunks) {
    EXPECT_TRUE(box.hi.x - box.lo.x < 0.2) << "a chunk spans the gap between the blades";
    area += (box.hi.x - box.lo.x) * (box.hi.y - box.lo.y);
  }
  EXPECT_LT(area, 0.1 * 2.1 * 2.0);

  positions[0] = std::nanf("");  // a non-finite corner is left out of its box
  const std::vector<Box> without_nan = aq::view_bounds::triangle_chunk_boxes(mesh, 4);
  ASSERT_EQ(without_nan.size(), 9u);
  EXPECT_TRUE(std::isfinite(without_nan[0].lo.x));
  mesh.indices = nullptr;
  EXPECT_TRUE(aq::view_bounds::triangle_chunk_boxes(mesh, 4).empty());
}
