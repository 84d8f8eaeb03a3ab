// What the pigment plugin's three nodes share: the dynamic canvas of screen anchoring (Cunzi et
// al. 2003; `pigment` and `pigment_canvas`): the view's pan and zoom from the camera, the
// uniforms of pigment.frag that the canvas densities depend on and the density textures'
// samplers; and the descriptions of the ports and parameters they have in common.
#pragma once

#include <aquarelle/plugin.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <string>

namespace pigment {

constexpr double kPi = 3.14159265358979323846;

// The density image inputs of `pigment` and `pigment_canvas`, in this order. Density textures
// in [0, 1]: 8 bits a channel are enough (a density step of 1/255 moves a colour by at most
// weight/510), so the host may store them as RGBA8 (README, "Cost").
// The density weights of `pigment` and `pigment_apply` (turbulence, grain, paper), and the
// procedural textures' seed of `pigment` and `pigment_canvas`.
inline constexpr aq_param_desc kWeightParams[3] = {
    aq::float_param("turbulence_weight", 1.6, 0.0, 4.0,
                    "d = 1 + weight · n for the low-frequency turbulence; 0 disables it"),
    aq::float_param("grain_weight", 1.0, 0.0, 4.0, "weight of the pigment dispersion"),
    aq::float_param("paper_weight", 1.6, 0.0, 4.0,
                    "weight of the paper grain (n = 0.5 − height: darker in the valleys)")};
inline constexpr aq_param_desc kSeedParam =
    aq::int_param("seed", 0, 0, 1 << 20, "independent procedural textures per seed");

inline constexpr aq_port_desc kDensityPorts[3] = {
    aq_port_desc{"turbulence", AQ_PORT_IMAGE, AQ_PORT_OPTIONAL | AQ_PORT_8BIT_ENOUGH,
                 "low-frequency density in red (0.5 = none); unconnected: fBm (Perlin)"},
    aq_port_desc{"grain", AQ_PORT_IMAGE, AQ_PORT_OPTIONAL | AQ_PORT_8BIT_ENOUGH,
                 "high-frequency pigment dispersion in red (0.5 = none); "
                 "unconnected: Gaussian noise"},
    aq_port_desc{"paper", AQ_PORT_IMAGE, AQ_PORT_OPTIONAL | AQ_PORT_8BIT_ENOUGH,
                 "paper height in red (0.5 = none; pigment settles where it is low); "
                 "unconnected: Worley cells"}};

// The dynamic canvas follows the camera: turning by an angle moves the canvas with the scene
// content at the image centre (1 / (2 tan(fov/2)) image heights per radian), and moving towards
// the target zooms it by the change of log2 distance.
struct Canvas {
  double pan_x = 0.0;
  double pan_y = 0.0;
  double zoom = 0.0;
};

inline Canvas canvas_for(const aq_scene* scene) {
  Canvas canvas;
  if (scene == nullptr) return canvas;
  const aq_camera& camera = scene->camera;
  double f[3];
  double length = 0.0;
  for (int k = 0; k < 3; ++k) {
    f[k] = static_cast<double>(camera.target[k]) - camera.position[k];
    length += f[k] * f[k];
  }
  length = std::sqrt(length);
  if (!(length > 0.0) || !std::isfinite(length)) return canvas;
  for (double& component : f) component /= length;
  const double yaw = std::atan2(f[0], -f[2]);  // 0 looking down −z, positive turning right
  const double pitch = std::asin(std::clamp(f[1], -1.0, 1.0));
  const double fov = std::clamp(static_cast<double>(camera.fov_y_degrees), 1.0, 179.0) * kPi / 180;
  const double heights_per_radian = 1.0 / (2.0 * std::tan(fov / 2.0));
  canvas.pan_x = yaw * heights_per_radian;
  canvas.pan_y = pitch * heights_per_radian;
  canvas.zoom = -std::log2(length);
  return canvas;
}

// What the procedural densities depend on besides the view.
struct DensityParams {
  std::array<float, 3> frequencies{};  // turbulence, grain, paper: cells per image height
  double world_scale = 1.0;
  int64_t seed = 0;
};

inline void set_canvas_uniforms(GLuint program, const DensityParams& params, double aspect,
                                const Canvas& canvas) {
  glUniform1fv(glGetUniformLocation(program, "u_frequencies"), 3, params.frequencies.data());
  aq::set_float(program, "u_world_scale", params.world_scale);
  aq::set_float(program, "u_seed", static_cast<double>(params.seed));
  aq::set_float(program, "u_aspect", aspect);
  aq::set_vec2(program, "u_pan", canvas.pan_x, canvas.pan_y);
  aq::set_float(program, "u_zoom", canvas.zoom);
}

// The `#define`s of the canvas part of a pigment.frag variant: each density's mode (0 off,
// 1 input image, 2 procedural) and whether the zoom blends two layers.
inline std::string canvas_defines(const std::array<int, 3>& modes, const Canvas& canvas) {
  const char* names[3] = {"AQ_PIGMENT_TURBULENCE", "AQ_PIGMENT_GRAIN", "AQ_PIGMENT_PAPER"};
  std::string defines;
  for (uint32_t i = 0; i < 3; ++i)
    defines += std::string("#define ") + names[i] + " " + std::to_string(modes[i]) + "\n";
  defines += std::string("#define AQ_PIGMENT_TWO_LAYERS ") +
             (canvas.zoom != std::floor(canvas.zoom) ? "1" : "0") + "\n";
  return defines;
}

// Binds the density inputs (turbulence, grain, paper at inputs first..first+2) to units 1-3 as
// `u_textures`, `stand_in` for unconnected ones so every sampler names a complete texture.
inline void bind_density_textures(aq::Context& ctx, GLuint program, uint32_t first,
                                  GLuint stand_in) {
  std::array<GLint, 3> units{1, 2, 3};
  for (uint32_t i = 0; i < 3; ++i) {
    glBindTextureUnit(1 + i,
                      ctx.connected(first + i) ? ctx.input_image(first + i).texture : stand_in);
  }
  glUniform1iv(glGetUniformLocation(program, "u_textures"), 3, units.data());
}

}  // namespace pigment
