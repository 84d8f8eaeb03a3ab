// Camera and light matrices of an aq_scene, shared by every node that rasterises a scene or
// looks a point up in a shadow map (gbuffer, shadowmap, cel_light). The light matrix must be
// bit-identical in the node that writes the shadow map and the node that reads it, so it is
// computed here, once, from what both nodes have: the scene, the render's aspect ratio and the
// shadow map's size (never from a node's own parameters).
//
//   world ──camera_view──► view ──camera_projection──► clip        (gbuffer)
//   world ──light_view_projection──────────────────► clip, z in [-1, 1] (shadowmap, cel_light)
//            fitted to the scene, or to the receivers in view (fit_to_view, view_bounds.hpp)
//
// Header-only; depends on plugin.h and glm only, so plugins and tests may include it.
#pragma once

#include <aquarelle/plugin.h>
#include <aquarelle/sdk/view_bounds.hpp>

#include <glm/glm.hpp>
#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/type_ptr.hpp>

#include <algorithm>
#include <cmath>
#include <optional>
#include <span>
#include <vector>

namespace aq::scene_math {

inline glm::vec3 to_vec3(const float* v) {
  return glm::vec3(v[0], v[1], v[2]);
}

// An up vector not parallel to `forward`, so lookAt never degenerates (a light or camera
// looking straight down is a normal case here: caustics come from above).
inline glm::vec3 stable_up(const glm::vec3& forward, const glm::vec3& preferred) {
  glm::vec3 up = glm::length(preferred) > 0.0f ? glm::normalize(preferred) : glm::vec3(0, 1, 0);
  if (std::abs(glm::dot(glm::normalize(forward), up)) > 0.999f) {
    up = std::abs(forward.z) < 0.9f ? glm::vec3(0, 0, 1) : glm::vec3(1, 0, 0);
  }
  return up;
}

inline glm::mat4 camera_view(const aq_camera& camera) {
  glm::vec3 eye = to_vec3(camera.position);
  glm::vec3 target = to_vec3(camera.target);
  if (glm::length(target - eye) < 1e-6f) target = eye + glm::vec3(0, 0, -1);
  return glm::lookAt(eye, target, stable_up(target - eye, to_vec3(camera.up)));
}

// The camera's rays for a full-screen pass: the pixel at normalised device coordinates (x, y)
// looks along forward + x·right + y·up, with right and up scaled by the half field of view
// (clamped as camera_projection clamps it), so the rays meet the g-buffer's pixels.
struct CameraRays {
  double forward[3];
  double right[3];
  double up[3];
};

inline CameraRays camera_rays(const aq_camera& camera, double aspect) {
  // The view matrix's rows are right, up and -forward.
  const glm::mat4 view = camera_view(camera);
  const double fov = std::clamp(double(camera.fov_y_degrees), 1.0, 179.0);
  const double tan_half = std::tan(fov * 3.14159265358979 / 360.0);
  CameraRays rays{};
  for (int axis = 0; axis < 3; ++axis) {
    rays.forward[axis] = -view[axis][2];
    rays.right[axis] = view[axis][0] * tan_half * aspect;
    rays.up[axis] = view[axis][1] * tan_half;
  }
  return rays;
}

inline glm::mat4 camera_projection(const aq_camera& camera, float aspect) {
  float fov = std::clamp(camera.fov_y_degrees, 1.0f, 179.0f);
  float near_plane = std::max(camera.near_plane, 1e-4f);
  float far_plane = std::max(camera.far_plane, near_plane * 2.0f);
  return glm::perspective(glm::radians(fov), std::max(aspect, 1e-6f), near_plane, far_plane);
}

// Direction light travels (into the scene), unit; a zero direction falls back to straight down.
inline glm::vec3 light_direction(const aq_scene& scene) {
  glm::vec3 d = to_vec3(scene.light.direction);
  float len = glm::length(d);
  return len > 1e-8f && std::isfinite(len) ? d / len : glm::vec3(0, -1, 0);
}

// The light's frame: its view (looking along the light at the centre of the scene bounds, a
// fallback box when the bounds are empty), the bounds in that view space and their radius.
// Every light matrix below starts from it, so writer and reader share each float operation.
struct LightFrame {
  glm::mat4 view;
  glm::vec3 vmin, vmax;  // the scene's bounds in light view space
  float radius;
};

inline LightFrame light_frame(const aq_scene& scene) {
  glm::vec3 lo = to_vec3(scene.bounds_min);
  glm::vec3 hi = to_vec3(scene.bounds_max);
  if (!(hi.x >= lo.x && hi.y >= lo.y && hi.z >= lo.z)) {
    lo = glm::vec3(-1.0f);
    hi = glm::vec3(1.0f);
  }
  glm::vec3 centre = 0.5f * (lo + hi);
  LightFrame frame;
  frame.radius = std::max(0.5f * glm::length(hi - lo), 1e-3f);
  glm::vec3 dir = light_direction(scene);
  frame.view = glm::lookAt(centre - dir * (2.0f * frame.radius), centre, stable_up(dir, {0, 1, 0}));
  frame.vmin = glm::vec3(1e30f);
  frame.vmax = glm::vec3(-1e30f);
  for (int corner = 0; corner < 8; ++corner) {
    glm::vec3 p((corner & 1) ? hi.x : lo.x, (corner & 2) ? hi.y : lo.y, (corner & 4) ? hi.z : lo.z);
    glm::vec3 v = glm::vec3(frame.view * glm::vec4(p, 1.0f));
    frame.vmin = glm::min(frame.vmin, v);
    frame.vmax = glm::max(frame.vmax, v);
  }
  return frame;
}

// Orthographic view-projection from the light, fitted tightly to the scene's bounds: the eight
// corners of the bounding box are taken to light view space and the box they span (with a
// small margin in depth so nothing is clipped) becomes the projection volume. Depth written
// through it (gl_FragCoord.z) is the same quantity cel_light recomputes as 0.5 * ndc.z + 0.5.
inline glm::mat4 light_view_projection(const aq_scene& scene) {
  const LightFrame f = light_frame(scene);
  // Square-ish texels are not needed; a degenerate (flat) extent is widened to stay invertible.
  float pad = 1e-3f * f.radius;
  glm::mat4 projection = glm::ortho(f.vmin.x - pad, f.vmax.x + pad, f.vmin.y - pad, f.vmax.y + pad,
                                    -f.vmax.z - 0.01f * f.radius, -f.vmin.z + 0.01f * f.radius);
  return projection * f.view;
}

// ---- What the camera sees of the scene ---------------------------------------------------
//
// The receivers in view are the meshes' boxes clipped to the camera's frustum (and to any extra
// half-space, e.g. under the water): view_bounds.hpp. Internal textures are sized from them.

// The camera's view-projection at `aspect` (width / height of the render), as the gbuffer
// draws it.
inline glm::dmat4 camera_view_projection(const aq_camera& camera, float aspect) {
  return glm::dmat4(camera_projection(camera, aspect)) * glm::dmat4(camera_view(camera));
}

// Vertices of the receivers in view: each mesh box ∩ the frustum ∩ every `extra` half-space.
inline std::vector<glm::dvec3> visible_receivers(const aq_scene& scene,
                                                 std::span<const view_bounds::Box> mesh_boxes,
                                                 float aspect,
                                                 std::span<const view_bounds::Plane> extra = {}) {
  const auto frustum = view_bounds::frustum_planes(camera_view_projection(scene.camera, aspect));
  std::vector<view_bounds::Plane> planes(frustum.begin(), frustum.end());
  planes.insert(planes.end(), extra.begin(), extra.end());
  return view_bounds::visible_points(mesh_boxes, planes);
}

// Camera depth of the nearest of `points` (nullopt for none), at least the near plane.
inline std::optional<double> nearest_receiver_depth(const aq_camera& camera,
                                                    std::span<const glm::dvec3> points) {
  const auto nearest = view_bounds::nearest_depth(points, glm::dmat4(camera_view(camera)));
  if (!nearest) return std::nullopt;
  return std::max<double>(*nearest, camera.near_plane);
}

// Texels for about one texel per screen pixel across `world_extent` world units seen at
// `depth` (a pinhole camera shows a world unit facing it at depth z on H / (2 tan(fov/2) z)
// pixels, the most it shows of a unit in any direction): rounded up to a multiple of
// `multiple`, at least min(16, largest), at most `largest`.
inline int footprint_texels(double world_extent, const aq_camera& camera, int height_pixels,
                            double depth, int multiple, int largest) {
  const double needed =
      world_extent * view_bounds::pixels_per_world_unit(camera.fov_y_degrees, height_pixels, depth);
  const double rounded = std::ceil(std::min(needed, 1e6) / multiple) * multiple;
  return std::clamp(static_cast<int>(rounded), std::min(16, largest), largest);
}

// ---- Fitting the shadow map to what the camera sees ----------------------------------------
//
// A texel of a map fitted to the whole scene is wasted wherever the camera cannot see. Only
// receivers in view need shadow texels; a caster that shadows one lies on the light ray through
// it, so inside the same light-space rectangle, and the depth range stays the scene's (casters
// out of view still cast).

struct ViewFit {
  bool any_visible = false;     // false: nothing of the scene in view; the scene fit is used
  glm::dvec2 lo{0.0}, hi{0.0};  // receivers in view, light view space xy, within the scene's
  double nearest_depth = 0.0;   // camera depth of the nearest receiver point in view
};

inline ViewFit fit_to_view(const aq_scene& scene, std::span<const view_bounds::Box> mesh_boxes,
                           float aspect) {
  ViewFit fit;
  const std::vector<glm::dvec3> points = visible_receivers(scene, mesh_boxes, aspect);
  if (points.empty()) return fit;
  const LightFrame frame = light_frame(scene);
  const glm::dmat4 view(frame.view);
  fit.lo = glm::dvec2(1e300);
  fit.hi = glm::dvec2(-1e300);
  for (const glm::dvec3& p : points) {
    const glm::dvec2 q(view * glm::dvec4(p, 1.0));
    fit.lo = glm::min(fit.lo, q);
    fit.hi = glm::max(fit.hi, q);
  }
  fit.lo = glm::max(fit.lo, glm::dvec2(frame.vmin.x, frame.vmin.y));
  fit.hi = glm::min(fit.hi, glm::dvec2(frame.vmax.x, frame.vmax.y));
  fit.any_visible = fit.hi.x >= fit.lo.x && fit.hi.y >= fit.lo.y;
  fit.nearest_depth = *nearest_receiver_depth(scene.camera, points);
  return fit;
}

// Shadow map texels for about one texel per screen pixel at the nearest receiver in view (the
// densest place the map is looked up), at most `max_size`, a multiple of 16, at least 16.
inline int shadow_size_for_view(const ViewFit& fit, const aq_camera& camera, int height_pixels,
                                int max_size) {
  max_size = std::max(16, max_size);
  if (!fit.any_visible) return max_size;
  const double extent = std::max(fit.hi.x - fit.lo.x, fit.hi.y - fit.lo.y);
  return footprint_texels(extent, camera, height_pixels, fit.nearest_depth, 16, max_size);
}

// The light's view-projection fitted to the receivers in view, for a `map_size` map. Shadow
// edges must not crawl as the camera moves: the window's size steps in sixteenths of the
// scene's extent and its origin moves in whole texels, so a texel keeps its place in the world
// until the window's size changes step.
inline glm::mat4 light_view_projection(const aq_scene& scene, const ViewFit& fit, int map_size) {
  if (!fit.any_visible || map_size < 2) return light_view_projection(scene);
  const LightFrame f = light_frame(scene);
  const double pad = 1e-3 * f.radius;
  const glm::dvec2 scene_lo = glm::dvec2(f.vmin.x, f.vmin.y) - pad;
  const glm::dvec2 scene_hi = glm::dvec2(f.vmax.x, f.vmax.y) + pad;
  glm::dvec2 lo = scene_lo, hi = scene_hi;
  const double size = static_cast<double>(map_size);
  for (int axis = 0; axis < 2; ++axis) {
    const double scene_extent = scene_hi[axis] - scene_lo[axis];
    const double step = scene_extent / 16.0;
    // One texel more than the receivers span, so snapping the origin down keeps them inside.
    const double wanted = (fit.hi[axis] - fit.lo[axis]) * size / (size - 1.0) + 2.0 * pad;
    const double extent = std::min(scene_extent, std::max(step, std::ceil(wanted / step) * step));
    if (extent >= scene_extent) continue;  // the whole scene: nothing to gain
    const double texel = extent / size;
    lo[axis] = std::floor((fit.lo[axis] - pad) / texel) * texel;
    hi[axis] = lo[axis] + extent;
  }
  glm::mat4 projection = glm::ortho(static_cast<float>(lo.x), static_cast<float>(hi.x),
                                    static_cast<float>(lo.y), static_cast<float>(hi.y),
                                    -f.vmax.z - 0.01f * f.radius, -f.vmin.z + 0.01f * f.radius);
  return projection * f.view;
}

}  // namespace aq::scene_math
