// vignette: radial darkening towards the corners, the seed's second underwater effect
// (Paré-Vogt & Chaid §5.2): colour *= 1 - remap(d, radius, corner, 0, strength), with d the
// distance to the image centre measured aspect-correctly (in units of the shorter side).
#include <aquarelle/plugin.hpp>

#include <algorithm>
#include <cmath>
#include <string>

#include "vignette_shaders.h"

namespace {

constexpr aq_port_desc kInputs[] = {aq::image_port("image", "colour to darken")};
constexpr aq_port_desc kOutputs[] = {aq::image_port("image", "darkened colour")};
enum Param { kRadius, kStrength, kSoftness };
constexpr aq_param_desc kParams[] = {
    aq::float_param("radius", 0.45, 0.0, 2.0,
                    "distance from the centre where darkening starts, in units of the image's "
                    "shorter side (a square image's corner is at 0.707)"),
    aq::float_param("strength", 0.7, 0.0, 1.0,
                    "darkening reached at the corners: 0 keeps the image, 1 makes them black"),
    aq::float_param("softness", 1.0, 0.0, 1.0,
                    "fraction of the way from `radius` to the corner over which darkening ramps "
                    "up linearly: 1 is the seed's ramp, 0 a hard edge")};

// Distance from the centre to a corner, in units of the shorter side.
double corner_distance(int width, int height) {
  return 0.5 * std::hypot(width, height) / std::min(width, height);
}

struct Vignette {
  std::string fragment = aq::pointwise_fragment(shaders::vignette_glsl.text);

  int process(aq::Context& ctx) {
    aq_image in = ctx.input_image(0);
    const double radius = ctx.param_float(kRadius);
    const double strength = ctx.param_float(kStrength);
    const double corner = corner_distance(in.width, in.height);
    // No pixel centre reaches the corner, so radius >= corner darkens nothing: pass through.
    if (strength <= 0.0 || radius >= corner) return ctx.pass_through(0, 0) ? AQ_OK : AQ_ERROR;
    aq_image out;
    if (!ctx.output_like(0, in, &out)) return AQ_ERROR;
    GLuint program = ctx.program(aq_shader_source{"vignette.glsl", fragment.c_str(), nullptr});
    if (program == 0) return AQ_ERROR;
    glUseProgram(program);
    aq::bind_texture(program, "u_image", 0, in);
    set_uniforms_for(ctx, program, "u_", in.width, in.height);
    bool drawn = ctx.draw(out);
    aq::unbind_textures(1);
    return drawn ? AQ_OK : AQ_ERROR;
  }

  // The uniforms of vignette.glsl, named prefix + name (the host fuses this node's function
  // into a pass of ctx's size).
  int set_uniforms(aq::Context& ctx, GLuint program, const std::string& prefix) {
    set_uniforms_for(ctx, program, prefix, ctx.width(), ctx.height());
    return AQ_OK;
  }

  // The ramp depends on the image's shape (its corner distance), so the size is the image's.
  void set_uniforms_for(aq::Context& ctx, GLuint program, const std::string& prefix, int width,
                        int height) {
    const double radius = ctx.param_float(kRadius);
    const double corner = corner_distance(width, height);
    aq::set_float(program, (prefix + "radius").c_str(), radius);
    aq::set_float(program, (prefix + "ramp").c_str(),
                  ctx.param_float(kSoftness) * std::max(0.0, corner - radius));
    aq::set_float(program, (prefix + "strength").c_str(), ctx.param_float(kStrength));
  }
};

}  // namespace

AQ_POINTWISE_NODE(kVignetteNode, Vignette, "vignette", "Color",
                  "Darkens the image towards its corners (aspect-correct radial ramp).", kInputs,
                  kOutputs, kParams, shaders::vignette_glsl, 0);
AQ_PLUGIN("vignette", "1.0", &kVignetteNode)
