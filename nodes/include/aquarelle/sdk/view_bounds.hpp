// What part of a scene the camera can see, as geometry: the bounding boxes of the meshes
// clipped to the view frustum (and to any extra half-space, e.g. "below the water"). Nodes use
// it to size internal textures from what the output can show: the caustic texture from the
// on-screen footprint of its tile at the nearest visible receiver, the shadow map from the
// receivers in view (scene_math.hpp's view-fitted light matrix).
//
//   mesh boxes (world) ──► ∩ frustum ∩ extra planes ──► polytope vertices ──► nearest depth,
//                                                                        light-space extent
//
// The clipped region of a box is a convex polytope; every linear function (view depth, a
// light-space coordinate) takes its extremes at its vertices, so those are all we compute:
// the box faces clipped by every plane (Sutherland–Hodgman), plus the points where three
// planes meet inside everything. Conservative by construction: boxes contain their meshes.
//
// Header-only; depends on plugin.h and glm only, so plugins and tests may include it. Double
// precision, and the same code in every node, so two nodes given the same scene agree exactly.
#pragma once

#include <aquarelle/plugin.h>

#include <glm/glm.hpp>
#include <glm/gtc/matrix_transform.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <optional>
#include <span>
#include <vector>

namespace aq::view_bounds {

struct Box {
  glm::dvec3 lo{1e300};
  glm::dvec3 hi{-1e300};
  bool empty() const { return !(hi.x >= lo.x && hi.y >= lo.y && hi.z >= lo.z); }
  void add(const glm::dvec3& p) {
    lo = glm::min(lo, p);
    hi = glm::max(hi, p);
  }
  glm::dvec3 corner(int i) const {
    return {(i & 1) ? hi.x : lo.x, (i & 2) ? hi.y : lo.y, (i & 4) ? hi.z : lo.z};
  }
};

// A half-space: points p with dot(xyz, p) + w >= 0 are inside.
using Plane = glm::dvec4;

inline double signed_distance(const Plane& plane, const glm::dvec3& p) {
  return glm::dot(glm::dvec3(plane), p) + plane.w;
}

// The six planes of the clip volume of `view_projection` (OpenGL: -w <= x, y, z <= w), inside
// facing (Gribb & Hartmann's row combinations).
inline std::array<Plane, 6> frustum_planes(const glm::dmat4& view_projection) {
  const glm::dmat4 t = glm::transpose(view_projection);  // t[i] is row i
  return {t[3] + t[0], t[3] - t[0], t[3] + t[1], t[3] - t[1], t[3] + t[2], t[3] - t[2]};
}

// A plane keeping y <= height (receivers under the water surface).
inline Plane below(double height) {
  return {0.0, -1.0, 0.0, height};
}

namespace detail {

inline std::vector<glm::dvec3> clip_polygon(const std::vector<glm::dvec3>& polygon,
                                            const Plane& plane) {
  std::vector<glm::dvec3> out;
  for (size_t i = 0; i < polygon.size(); ++i) {
    const glm::dvec3& a = polygon[i];
    const glm::dvec3& b = polygon[(i + 1) % polygon.size()];
    const double da = signed_distance(plane, a);
    const double db = signed_distance(plane, b);
    if (da >= 0.0) out.push_back(a);
    if ((da >= 0.0) != (db >= 0.0)) out.push_back(a + (b - a) * (da / (da - db)));
  }
  return out;
}

inline bool inside(const glm::dvec3& p, const Box& box, std::span<const Plane> planes,
                   double tolerance) {
  for (int k = 0; k < 3; ++k) {
    if (p[k] < box.lo[k] - tolerance || p[k] > box.hi[k] + tolerance) return false;
  }
  for (const Plane& plane : planes) {
    if (signed_distance(plane, p) < -tolerance * glm::length(glm::dvec3(plane))) return false;
  }
  return true;
}

}  // namespace detail

// Vertices of box ∩ every half-space in `planes` (empty if the intersection is empty).
inline std::vector<glm::dvec3> clip_box(const Box& box, std::span<const Plane> planes) {
  std::vector<glm::dvec3> vertices;
  if (box.empty()) return vertices;
  // Faces of the box as corner indices, each a quad in order around it.
  static constexpr int kFaces[6][4] = {{0, 2, 6, 4}, {1, 3, 7, 5}, {0, 1, 5, 4},
                                       {2, 3, 7, 6}, {0, 1, 3, 2}, {4, 5, 7, 6}};
  for (const auto& face : kFaces) {
    std::vector<glm::dvec3> polygon;
    for (int corner : face) polygon.push_back(box.corner(corner));
    for (const Plane& plane : planes) {
      polygon = detail::clip_polygon(polygon, plane);
      if (polygon.empty()) break;
    }
    vertices.insert(vertices.end(), polygon.begin(), polygon.end());
  }
  // Vertices on no box face: three planes meeting inside the box (a frustum corner, or where
  // the water plane crosses a frustum edge).
  const double tolerance = 1e-9 * std::max(1.0, glm::length(box.hi - box.lo));
  for (size_t i = 0; i < planes.size(); ++i) {
    for (size_t j = i + 1; j < planes.size(); ++j) {
      for (size_t k = j + 1; k < planes.size(); ++k) {
        const glm::dmat3 normals = glm::transpose(
            glm::dmat3(glm::dvec3(planes[i]), glm::dvec3(planes[j]), glm::dvec3(planes[k])));
        const double det = glm::determinant(normals);
        if (std::abs(det) < 1e-12) continue;
        const glm::dvec3 p =
            glm::inverse(normals) * glm::dvec3(-planes[i].w, -planes[j].w, -planes[k].w);
        if (detail::inside(p, box, planes, tolerance)) vertices.push_back(p);
      }
    }
  }
  return vertices;
}

// World-space boxes of a scene's meshes, from their vertex data (object-space boxes are cached
// per geometry revision, so a still mesh is not re-scanned each frame).
class MeshBoxes {
 public:
  const std::vector<Box>& world_boxes(const aq_scene& scene) {
    world_.assign(scene.mesh_count, Box{});
    object_.resize(scene.mesh_count);
    for (uint32_t i = 0; i < scene.mesh_count; ++i) {
      const aq_mesh& mesh = scene.meshes[i];
      Cached& cached = object_[i];
      if (!cached.valid || cached.revision != mesh.geometry_revision) {
        cached.box = Box{};
        for (uint32_t v = 0; mesh.positions != nullptr && v < mesh.vertex_count; ++v) {
          const float* p = mesh.positions + 3 * static_cast<size_t>(v);
          if (std::isfinite(p[0]) && std::isfinite(p[1]) && std::isfinite(p[2])) {
            cached.box.add(glm::dvec3(p[0], p[1], p[2]));
          }
        }
        cached.revision = mesh.geometry_revision;
        cached.valid = true;
      }
      if (cached.box.empty()) continue;
      glm::dmat4 model;
      for (int c = 0; c < 16; ++c) model[c / 4][c % 4] = mesh.model[c];
      for (int corner = 0; corner < 8; ++corner) {
        world_[i].add(glm::dvec3(model * glm::dvec4(cached.box.corner(corner), 1.0)));
      }
    }
    return world_;
  }

 private:
  struct Cached {
    bool valid = false;
    uint64_t revision = 0;
    Box box;
  };
  std::vector<Cached> object_;
  std::vector<Box> world_;
};

// World-space boxes of a mesh's triangles, `triangles_per_chunk` consecutive triangles each:
// a finer cover than the mesh's one box. A triangle's pixels lie inside the projection of its
// corners, so the chunks' projected boxes together cover the mesh; for a moving mesh made of
// thin parts (seaweed blades, a fish's fins) they cover a small part of its box's projection.
// Indices out of range or non-finite corners are skipped; an empty result means "use the
// mesh's box".
inline std::vector<Box> triangle_chunk_boxes(const aq_mesh& mesh, uint32_t triangles_per_chunk) {
  std::vector<Box> boxes;
  if (mesh.positions == nullptr || mesh.indices == nullptr || triangles_per_chunk == 0)
    return boxes;
  glm::dmat4 model;
  for (int c = 0; c < 16; ++c) model[c / 4][c % 4] = mesh.model[c];
  const uint32_t per_chunk = 3 * triangles_per_chunk;
  const uint32_t index_count = mesh.index_count - mesh.index_count % 3;
  for (uint32_t first = 0; first < index_count; first += per_chunk) {
    Box object;
    const uint32_t end = std::min(index_count, first + per_chunk);
    for (uint32_t k = first; k < end; ++k) {
      const uint32_t v = mesh.indices[k];
      if (v >= mesh.vertex_count) continue;
      const float* p = mesh.positions + 3 * static_cast<size_t>(v);
      if (std::isfinite(p[0]) && std::isfinite(p[1]) && std::isfinite(p[2]))
        object.add(glm::dvec3(p[0], p[1], p[2]));
    }
    if (object.empty()) continue;
    Box world;
    for (int corner = 0; corner < 8; ++corner)
      world.add(glm::dvec3(model * glm::dvec4(object.corner(corner), 1.0)));
    boxes.push_back(world);
  }
  return boxes;
}

// Every vertex of (each box ∩ planes); empty when no box reaches into the planes.
inline std::vector<glm::dvec3> visible_points(std::span<const Box> boxes,
                                              std::span<const Plane> planes) {
  std::vector<glm::dvec3> points;
  for (const Box& box : boxes) {
    std::vector<glm::dvec3> clipped = clip_box(box, planes);
    points.insert(points.end(), clipped.begin(), clipped.end());
  }
  return points;
}

// Distance along the camera's viewing axis of the nearest point (nullopt for none).
inline std::optional<double> nearest_depth(std::span<const glm::dvec3> points,
                                           const glm::dmat4& view) {
  std::optional<double> nearest;
  for (const glm::dvec3& p : points) {
    const double depth = -(view * glm::dvec4(p, 1.0)).z;
    if (!nearest || depth < *nearest) nearest = depth;
  }
  return nearest;
}

// Screen pixels covered by one world unit facing the camera at `depth` along the view axis,
// for a perspective camera with vertical field of view `fov_y_degrees` and `height_pixels`
// rows.
inline double pixels_per_world_unit(double fov_y_degrees, int height_pixels, double depth) {
  const double fov = glm::radians(std::clamp(fov_y_degrees, 1.0, 179.0));
  return static_cast<double>(height_pixels) / (2.0 * std::tan(0.5 * fov) * std::max(depth, 1e-6));
}

}  // namespace aq::view_bounds
