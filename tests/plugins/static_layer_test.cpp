// The screen rectangles the g-buffer and the shadow map restore from their cached layer around
// the meshes that moved (aquarelle/sdk/static_layer.hpp covered_pixels): a mesh's rectangle
// holds every pixel its vertices project to and one around it, what its box clipped to the view
// frustum projects to when the mesh reaches behind the camera (the sand under it), nothing when
// it has no vertices or lies off the target.
#include <gtest/gtest.h>

#include <aquarelle/sdk/static_layer.hpp>

#include <glm/glm.hpp>
#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/type_ptr.hpp>

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

namespace aq {
namespace {

// A mesh of `positions` (and `indices`, when given) placed by `model`.
aq_mesh mesh_of(const std::vector<float>& positions, const glm::mat4& model,
                const std::vector<uint32_t>* indices = nullptr) {
  aq_mesh mesh{};
  mesh.positions = positions.data();
  mesh.vertex_count = static_cast<uint32_t>(positions.size() / 3);
  if (indices != nullptr) {
    mesh.indices = indices->data();
    mesh.index_count = static_cast<uint32_t>(indices->size());
  }
  std::copy(glm::value_ptr(model), glm::value_ptr(model) + 16, mesh.model);
  return mesh;
}

// A scene of that one mesh.
aq_scene scene_of(const aq_mesh& mesh) {
  aq_scene scene{};
  scene.struct_size = sizeof(aq_scene);
  scene.meshes = &mesh;
  scene.mesh_count = 1;
  return scene;
}

// The rectangle the g-buffer and the shadow map restore for a mesh of `positions` placed by
// `model`: its world box as they get it (view_bounds::MeshBoxes), projected.
PixelRect rect_of(const std::vector<float>& positions, const glm::mat4& model,
                  const glm::mat4& view_projection, int width, int height) {
  const aq_mesh mesh = mesh_of(positions, model);
  const aq_scene scene = scene_of(mesh);
  view_bounds::MeshBoxes boxes;
  return covered_pixels(boxes.world_boxes(scene)[0], glm::dmat4(view_projection), width, height);
}

TEST(CoveredPixels, EveryProjectedVertexLiesInTheRectangle) {
  std::mt19937 random(3);
  std::uniform_real_distribution<float> unit(-1.0f, 1.0f);
  const int width = 200, height = 120;
  const glm::mat4 projection = glm::perspective(glm::radians(50.0f), 200.0f / 120.0f, 0.1f, 100.0f);
  const glm::mat4 view = glm::lookAt(glm::vec3(0, 1, 6), glm::vec3(0, 0, 0), glm::vec3(0, 1, 0));
  const glm::mat4 view_projection = projection * view;
  int inside_tests = 0;
  for (int trial = 0; trial < 200; ++trial) {
    // Random points in a box and the box's corners: the corners are vertices, so the
    // rectangle's margin around the extreme vertices is the one under test.
    std::vector<float> positions;
    for (int v = 0; v < 22; ++v)
      for (int k = 0; k < 3; ++k) positions.push_back(0.8f * unit(random));
    for (int corner = 0; corner < 8; ++corner)
      for (int k = 0; k < 3; ++k) positions.push_back((corner >> k) & 1 ? 0.9f : -0.9f);
    // Every other mesh is only moved (its world box's corners are then vertices too), the
    // others also turned.
    glm::mat4 model = glm::translate(
        glm::mat4(1.0f), glm::vec3(2.5f * unit(random), unit(random), 2.0f * unit(random)));
    const float angle = 3.0f * unit(random);
    const glm::vec3 axis = glm::normalize(glm::vec3(unit(random), 1.0f, unit(random)));
    if (trial % 2 == 1) model = glm::rotate(model, angle, axis);
    const PixelRect rect = rect_of(positions, model, view_projection, width, height);
    EXPECT_LE(0, rect.x0);
    EXPECT_LE(rect.x1, width);
    EXPECT_LE(0, rect.y0);
    EXPECT_LE(rect.y1, height);
    for (int v = 0; v < 30; ++v) {
      const glm::vec4 clip =
          view_projection * model *
          glm::vec4(positions[3 * v], positions[3 * v + 1], positions[3 * v + 2], 1.0f);
      ASSERT_GT(clip.w, 0.0f);
      const float x = (clip.x / clip.w * 0.5f + 0.5f) * width;
      const float y = (clip.y / clip.w * 0.5f + 0.5f) * height;
      if (x < 0 || x >= width || y < 0 || y >= height) continue;  // off the target
      ++inside_tests;
      // The pixels a triangle through this vertex may light reach one pixel around it.
      EXPECT_LE(rect.x0, std::max(0, static_cast<int>(std::floor(x)) - 1));
      EXPECT_GE(rect.x1, std::min(width, static_cast<int>(std::ceil(x)) + 1));
      EXPECT_LE(rect.y0, std::max(0, static_cast<int>(std::floor(y)) - 1));
      EXPECT_GE(rect.y1, std::min(height, static_cast<int>(std::ceil(y)) + 1));
    }
  }
  EXPECT_GT(inside_tests, 1000);
}

// A floor reaching under and behind the camera: its box clipped to the frustum covers the lower
// part of the view, every point of it in view projects into the rectangle, and the upper part
// of the target stays out (the damage tracking of the light redraws the floor, not the water).
TEST(CoveredPixels, ABoxBehindTheCameraIsClippedToTheView) {
  const int width = 96, height = 64;
  const glm::mat4 projection = glm::perspective(glm::radians(50.0f), 1.5f, 0.1f, 100.0f);
  const glm::mat4 view =
      glm::lookAt(glm::vec3(0, 0, 2), glm::vec3(0, -0.3f, 0), glm::vec3(0, 1, 0));
  const glm::mat4 view_projection = projection * view;
  const std::vector<float> floor = {-3, -1.2f, -6, 3, -1.0f, 8};  // z to 8: behind the eye
  const PixelRect rect = rect_of(floor, glm::mat4(1.0f), view_projection, width, height);
  EXPECT_LT(rect.y1, height) << "the floor's rectangle reaches the top of the view";
  EXPECT_GT(rect.y1 - rect.y0, 0);
  std::mt19937 random(9);
  std::uniform_real_distribution<float> unit(0.0f, 1.0f);
  int seen = 0;
  for (int i = 0; i < 20000; ++i) {
    const glm::vec4 p(-3 + 6 * unit(random), -1.2f + 0.2f * unit(random), -6 + 14 * unit(random),
                      1);
    const glm::vec4 clip = view_projection * p;
    if (clip.w <= 0.1f) continue;
    const float x = (clip.x / clip.w * 0.5f + 0.5f) * width;
    const float y = (clip.y / clip.w * 0.5f + 0.5f) * height;
    if (x < 0 || x >= width || y < 0 || y >= height) continue;
    ++seen;
    EXPECT_LE(rect.x0, static_cast<int>(std::floor(x)));
    EXPECT_GT(rect.x1, static_cast<int>(std::floor(x)));
    EXPECT_LE(rect.y0, static_cast<int>(std::floor(y)));
    EXPECT_GT(rect.y1, static_cast<int>(std::floor(y)));
  }
  EXPECT_GT(seen, 1000);
}

TEST(CoveredPixels, AcrossTheWholeViewIsTheWholeTargetAndNoVerticesIsNothing) {
  const glm::mat4 projection = glm::perspective(glm::radians(50.0f), 1.0f, 0.1f, 100.0f);
  const glm::mat4 view = glm::lookAt(glm::vec3(0, 0, 2), glm::vec3(0, 0, 0), glm::vec3(0, 1, 0));
  const glm::mat4 view_projection = projection * view;
  const std::vector<float> across_the_camera = {-1, -1, -1, 1, 1, 5};  // z from -1 to 5 (eye at 2)
  const PixelRect all = rect_of(across_the_camera, glm::mat4(1.0f), view_projection, 64, 32);
  EXPECT_EQ(all.x0, 0);
  EXPECT_EQ(all.y0, 0);
  EXPECT_EQ(all.x1, 64);
  EXPECT_EQ(all.y1, 32);
  const std::vector<float> none;
  const PixelRect empty = rect_of(none, glm::mat4(1.0f), view_projection, 64, 32);
  EXPECT_LE(empty.x1 - empty.x0, 0);
  // Entirely off the target: an empty rectangle, nothing to restore.
  const std::vector<float> far_left = {-40, -0.1f, -1, -39, 0.1f, -0.5f};
  const PixelRect off = rect_of(far_left, glm::mat4(1.0f), view_projection, 64, 32);
  EXPECT_LE(off.x1 - off.x0, 0);
}

// Appends an upright blade of `segments` quads (two triangles each) at (x, y, 0) to a mesh.
void add_blade(std::vector<float>* positions, std::vector<uint32_t>* indices, float x, float y,
               float width, int segments, float segment_height) {
  const uint32_t base = static_cast<uint32_t>(positions->size() / 3);
  for (int k = 0; k <= segments; ++k) {
    const float yk = y + segment_height * static_cast<float>(k);
    positions->insert(positions->end(), {x, yk, 0.0f, x + width, yk, 0.0f});
  }
  for (uint32_t k = 0; k < static_cast<uint32_t>(segments); ++k) {
    const uint32_t a = base + 2 * k;
    indices->insert(indices->end(), {a, a + 1, a + 2, a + 1, a + 3, a + 2});
  }
}

// A camera 5 units in front of the blades' plane, a 2:1 view of 50 degrees.
glm::dmat4 blades_view_projection() {
  const glm::mat4 projection = glm::perspective(glm::radians(50.0f), 2.0f, 0.1f, 100.0f);
  const glm::mat4 view = glm::lookAt(glm::vec3(0, 0, 5), glm::vec3(0, 0, 0), glm::vec3(0, 1, 0));
  return glm::dmat4(projection * view);
}

// The pixel vertex v of `positions` projects into in a width x height target.
PixelRect pixel_of_vertex(const glm::dmat4& view_projection, const std::vector<float>& positions,
                          size_t v, int width, int height) {
  const glm::dvec4 clip =
      view_projection * glm::dvec4(positions[3 * v], positions[3 * v + 1], positions[3 * v + 2], 1);
  const int x = static_cast<int>(std::floor((clip.x / clip.w * 0.5 + 0.5) * width));
  const int y = static_cast<int>(std::floor((clip.y / clip.w * 0.5 + 0.5) * height));
  return PixelRect{x, y, x + 1, y + 1};
}

// A moving mesh of two thin upright blades at either side of the view (a seaweed cluster): what
// record() says may be covered holds every pixel of each blade's vertices, and not the open
// space between them, which the mesh's one box would span.
TEST(DrawnOverLayer, AMovingMeshCoversItsTrianglesNotItsWholeBox) {
  const glm::dmat4 view_projection = blades_view_projection();
  std::vector<float> positions;
  std::vector<uint32_t> indices;
  for (float x : {-3.0f, 3.0f}) add_blade(&positions, &indices, x, -1.0f, 0.05f, 4, 0.5f);
  const aq_mesh mesh = mesh_of(positions, glm::mat4(1.0f), &indices);
  const aq_scene scene = scene_of(mesh);
  view_bounds::MeshBoxes boxes;
  const CachedTargets layer;  // record() reads only its key; no GL
  DrawnOverLayer drawn;
  drawn.record(layer, scene, boxes.world_boxes(scene), {false}, view_projection, 256, 128);
  Region covered = drawn.moving();
  ASSERT_FALSE(covered.empty());
  for (size_t v = 0; v < positions.size() / 3; ++v) {
    const PixelRect pixel = pixel_of_vertex(view_projection, positions, v, 256, 128);
    EXPECT_TRUE(covered.covers(Region::of(pixel)))
        << "vertex " << v << " at pixel " << pixel.x0 << ", " << pixel.y0;
  }
  EXPECT_FALSE(covered.covers(Region::of(PixelRect{128, 64, 129, 65})))
      << "the gap between the blades is marked as covered";
  EXPECT_LT(covered.area(256, 128), 256 * 128 / 8);
}

// More moving pieces than a node draws rects (a meadow of blades): the layer is copied back in
// at most Region::kMaxDrawRects merged rects, but the damage declared downstream is the pixels
// the pieces' boxes cover, not the merged rects around them (the fish's box, merged with the
// seaweed's, made every later pass redraw open water).
TEST(DrawnOverLayer, TheDamageIsThePiecesBoxesNotTheRectsTheLayerIsCopiedIn) {
  const glm::dmat4 view_projection = blades_view_projection();
  std::vector<float> positions;
  std::vector<uint32_t> indices;
  for (int blade = 0; blade < 100; ++blade) {
    // Short blades on a staggered grid: 10 columns by 10 rows, none touching another.
    const float x = -4.0f + 0.8f * static_cast<float>(blade % 10) + 0.3f * ((blade / 10) % 2);
    const float y = -2.0f + 0.4f * static_cast<float>(blade / 10);
    // Two segments, four triangles: one chunk (DrawnOverLayer::kChunk) per blade.
    add_blade(&positions, &indices, x, y, 0.03f, 2, 0.075f);
  }
  const aq_mesh mesh = mesh_of(positions, glm::mat4(1.0f), &indices);
  const aq_scene scene = scene_of(mesh);
  view_bounds::MeshBoxes boxes;
  const CachedTargets layer;
  DrawnOverLayer drawn;
  drawn.record(layer, scene, boxes.world_boxes(scene), {false}, view_projection, 512, 256);
  const Region& damage = drawn.moving();
  ASSERT_GT(damage.rects().size(), Region::kMaxDrawRects);
  const Region merged = damage.for_drawing();
  EXPECT_TRUE(merged.covers(damage));
  EXPECT_LT(damage.area(512, 256), merged.area(512, 256) * 3 / 4)
      << "the declared damage is (nearly) the merged rects";
  for (size_t v = 0; v < positions.size() / 3; ++v) {
    const PixelRect pixel = pixel_of_vertex(view_projection, positions, v, 512, 256);
    if (pixel.x0 < 0 || pixel.y0 < 0 || pixel.x0 >= 512 || pixel.y0 >= 256) continue;
    EXPECT_TRUE(damage.covers(Region::of(pixel)))
        << "vertex " << v << " at pixel " << pixel.x0 << ", " << pixel.y0;
  }
}

}  // namespace
}  // namespace aq
