// The camera and the light as the `scene` and `scene_join` nodes take them from their
// parameters: one definition, so both nodes read the same values the same way.
#pragma once

#include <aquarelle/plugin.h>

#include <cmath>

// The parameters after the camera's position and target, in this order, in both nodes' kParams
// (their Param enums list kFov .. kCausticTile in the same order).
#define AQ_SCENE_VIEW_AND_WATER_PARAMS                                                         \
  aq::float_param("fov", 50.0, 5.0, 150.0, "vertical field of view in degrees", 0.0, "angle"), \
      aq::vec3_param("light_direction", 0.7, -1.0, -0.15, -1, 1,                               \
                     "direction the light travels (from the water surface down), normalised"), \
      aq::color_param("light_color", 1.0, 0.97, 0.9, "light colour (linear)"),                 \
      aq::float_param("light_intensity", 1.0, 0.0, 20.0, "light colour multiplier (HDR)"),     \
      aq::color_param("ambient", 0.32, 0.37, 0.42, "ambient light (linear)"),                  \
      aq::float_param("water_height", 6.0, -1000.0, 1000.0,                                    \
                      "world y of the water surface (caustic projection plane)"),              \
      aq::float_param("caustic_tile", 4.0, 0.01, 1000.0,                                       \
                      "world units one period of the water's caustic pattern covers")

namespace scene {

struct ViewParams {
  const double* eye;
  const double* target;
  double fov_degrees;
  const double* light_direction;  // need not be unit; zero means straight down
  const double* light_color;
  double light_intensity;
  const double* ambient;
};

inline void set_camera_and_light(const ViewParams& p, aq_scene* scene) {
  aq_camera& camera = scene->camera;
  for (int k = 0; k < 3; ++k) {
    camera.position[k] = static_cast<float>(p.eye[k]);
    camera.target[k] = static_cast<float>(p.target[k]);
    camera.up[k] = k == 1 ? 1.0f : 0.0f;
  }
  camera.fov_y_degrees = static_cast<float>(p.fov_degrees);
  camera.near_plane = 0.05f;
  camera.far_plane = 200.0f;
  const double* d = p.light_direction;
  const double length = std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
  for (int k = 0; k < 3; ++k) {
    scene->light.direction[k] =
        length > 1e-9 ? static_cast<float>(d[k] / length) : (k == 1 ? -1.0f : 0.0f);
    scene->light.color[k] = static_cast<float>(p.light_color[k] * p.light_intensity);
    scene->light.ambient[k] = static_cast<float>(p.ambient[k]);
  }
}

}  // namespace scene
