// Camera and light matrices of an aq_scene, shared by every node that rasterises a scene or
// looks a point up in a shadow map (gbuffer, shadowmap, cel_light). The light matrix must be
// bit-identical in the node that writes the shadow map and the node that reads it, so it is
// computed here, once, from the scene alone (never from a node's own parameters).
//
//   world ──camera_view──► view ──camera_projection──► clip        (gbuffer)
//   world ──light_view_projection──────────────────► clip, z in [-1, 1] (shadowmap, cel_light)
//
// Header-only; depends on plugin.h and glm only, so plugins and tests may include it.
#pragma once

#include <aquarelle/plugin.h>

#include <glm/glm.hpp>
#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/type_ptr.hpp>

#include <algorithm>
#include <cmath>

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

// Orthographic view-projection from the light, fitted tightly to the scene's bounds: the eight
// corners of the bounding box are taken to light view space and the box they span (with a
// small margin in depth so nothing is clipped) becomes the projection volume. Depth written
// through it (gl_FragCoord.z) is the same quantity cel_light recomputes as 0.5 * ndc.z + 0.5.
inline glm::mat4 light_view_projection(const aq_scene& scene) {
  glm::vec3 lo = to_vec3(scene.bounds_min);
  glm::vec3 hi = to_vec3(scene.bounds_max);
  if (!(hi.x >= lo.x && hi.y >= lo.y && hi.z >= lo.z)) {
    lo = glm::vec3(-1.0f);
    hi = glm::vec3(1.0f);
  }
  glm::vec3 centre = 0.5f * (lo + hi);
  float radius = std::max(0.5f * glm::length(hi - lo), 1e-3f);
  glm::vec3 dir = light_direction(scene);
  glm::mat4 view = glm::lookAt(centre - dir * (2.0f * radius), centre, stable_up(dir, {0, 1, 0}));
  glm::vec3 vmin(1e30f), vmax(-1e30f);
  for (int corner = 0; corner < 8; ++corner) {
    glm::vec3 p((corner & 1) ? hi.x : lo.x, (corner & 2) ? hi.y : lo.y, (corner & 4) ? hi.z : lo.z);
    glm::vec3 v = glm::vec3(view * glm::vec4(p, 1.0f));
    vmin = glm::min(vmin, v);
    vmax = glm::max(vmax, v);
  }
  // Square-ish texels are not needed; a degenerate (flat) extent is widened to stay invertible.
  float pad = 1e-3f * radius;
  glm::mat4 projection = glm::ortho(vmin.x - pad, vmax.x + pad, vmin.y - pad, vmax.y + pad,
                                    -vmax.z - 0.01f * radius, -vmin.z + 0.01f * radius);
  return projection * view;
}

}  // namespace aq::scene_math
