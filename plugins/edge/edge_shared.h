// What the edge plugin's three nodes share: the descriptions of the parameters `edge` has in
// common with `edge_detect` (detection) and `edge_apply` (darkening), and the detection's
// uniforms (aquarelle/edge_kernels.glsl, aq_edge_weight).
#pragma once

#include <aquarelle/plugin.hpp>

#include <algorithm>
#include <string>

namespace edge {

inline constexpr aq_param_desc kKernelParam =
    aq::enum_param("kernel", "laplacian|sobel", 0,
                   "laplacian: 3×3, −8 centre (the seed's kernel); sobel: gradient magnitude");
inline constexpr aq_param_desc kFactorParam = aq::float_param(
    "factor", 0.7, 0.0, 1.0, "HSV value multiplier on full edges; 1 passes the image through");
inline constexpr aq_param_desc kThresholdParam = aq::float_param(
    "threshold", 0.1, 0.0, 8.0, "edge response where darkening starts (largest channel response)");
inline constexpr aq_param_desc kSoftnessParam = aq::float_param(
    "softness", 0.2, 0.001, 8.0, "width of the smooth ramp above the threshold to full darkening");

// The detection's uniforms, named prefix + threshold, softness and sobel, from the parameters
// at these indices.
inline void set_detection_uniforms(aq::Context& ctx, GLuint program, const std::string& prefix,
                                   uint32_t kernel, uint32_t threshold, uint32_t softness) {
  aq::set_float(program, (prefix + "threshold").c_str(), ctx.param_float(threshold));
  aq::set_float(program, (prefix + "softness").c_str(), std::max(ctx.param_float(softness), 1e-3));
  aq::set_int(program, (prefix + "sobel").c_str(), ctx.param_enum(kernel) == 1 ? 1 : 0);
}

// The own pass of `edge` and `edge_apply` (when the host does not fuse them): the pointwise
// `fragment` over `in` into output 0, `second` bound as the sampler `u_<second_name>`, the rest
// of the uniforms from `set_uniforms(program)`. Returns AQ_OK or AQ_ERROR.
template <typename SetUniforms>
int draw_own_pass(aq::Context& ctx, const char* name, const std::string& fragment,
                  const aq_image& in, const char* second_name, const aq_image& second,
                  SetUniforms&& set_uniforms) {
  aq_image out;
  if (!ctx.output_like(0, in, &out)) return AQ_ERROR;
  const GLuint program = ctx.program(aq_shader_source{name, fragment.c_str(), nullptr});
  if (program == 0) return AQ_ERROR;
  glUseProgram(program);
  aq::bind_texture(program, "u_image", 0, in);
  aq::bind_texture(program, (std::string("u_") + second_name).c_str(), 1, second);
  set_uniforms(program);
  const bool drawn = ctx.draw(out);
  aq::unbind_textures(2);
  return drawn ? AQ_OK : AQ_ERROR;
}

}  // namespace edge
