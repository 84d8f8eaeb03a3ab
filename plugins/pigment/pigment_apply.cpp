// pigment_apply: the pigment densities of a `pigment_canvas` applied to an image (Bousseau et al.
// 2006, seed 000 §3.6) — the per-pixel half of `pigment`, as a pointwise node the host fuses
// into the pass before it (in graphs/underwater.json: the wobble's draw, with edge).
//
//   image ────────────────────────────────┐
//   density (pigment_canvas: n + 0.5) ────┴──► C ← C(1 − (1 − C)(d − 1)) three times ──► image
#include <aquarelle/plugin.hpp>

#include <array>
#include <string>

#include "pigment_shaders.h"
#include "pigment_shared.h"

namespace {

constexpr aq_port_desc kInputs[] = {
    aq::image_port("image", "colour to modulate"),
    // Densities in [0, 1]: a step of 1/255 moves a colour by at most weight/510 (README).
    aq_port_desc{"density", AQ_PORT_IMAGE, AQ_PORT_8BIT_ENOUGH,
                 "the canvas densities of `pigment_canvas`: r turbulence, g grain, b paper, "
                 "each n + 0.5 (0.5 = none)"}};
// AQ_PORT_HDR8: written encoded (aquarelle/hdr8.glsl) when every reader decodes it (blur).
constexpr aq_port_desc kOutputs[] = {
    aq::image_port("image", "colour with pigment density", AQ_PORT_HDR8)};
enum Input : uint32_t { kImage, kDensity };
enum Param : uint32_t { kTurbulenceWeight, kGrainWeight, kPaperWeight };
constexpr aq_param_desc kParams[] = {pigment::kWeightParams[0], pigment::kWeightParams[1],
                                     pigment::kWeightParams[2]};

struct PigmentApply {
  int process(aq::Context& ctx) {
    const aq_image in = ctx.input_image(kImage);
    if (ctx.param_float(kTurbulenceWeight) == 0.0 && ctx.param_float(kGrainWeight) == 0.0 &&
        ctx.param_float(kPaperWeight) == 0.0) {
      return ctx.pass_through(0, kImage) ? AQ_OK : AQ_ERROR;
    }
    aq_image out;
    if (!ctx.output_like(0, in, &out)) return AQ_ERROR;
    const bool encode = out.format == AQ_FORMAT_RGBA8_HDR;
    std::string& fragment = fragments_[encode ? 1 : 0];
    if (fragment.empty())
      fragment = aq::pointwise_fragment(shaders::pigment_apply_glsl.text, encode);
    const GLuint program =
        ctx.program(aq_shader_source{"pigment_apply.glsl", fragment.c_str(), nullptr});
    if (program == 0) return AQ_ERROR;
    glUseProgram(program);
    aq::bind_texture(program, "u_image", 0, in);
    aq::bind_texture(program, "u_density", 1, ctx.input_image(kDensity));
    set_uniforms(ctx, program, "u_");
    const bool drawn = ctx.draw(out);
    aq::unbind_textures(2);
    return drawn ? AQ_OK : AQ_ERROR;
  }

  // The uniforms of pigment_apply.glsl but the density, named prefix + name (the host binds the
  // density when it fuses this node's function).
  int set_uniforms(aq::Context& ctx, GLuint program, const std::string& prefix) {
    aq::set_vec3(program, (prefix + "weights").c_str(),
                 std::array<float, 3>{static_cast<float>(ctx.param_float(kTurbulenceWeight)),
                                      static_cast<float>(ctx.param_float(kGrainWeight)),
                                      static_cast<float>(ctx.param_float(kPaperWeight))}
                     .data());
    return AQ_OK;
  }

 private:
  std::array<std::string, 2> fragments_;  // linear output, 8-bit HDR output
};

}  // namespace

AQ_POINTWISE_NODE(kPigmentApplyNode, PigmentApply, "pigment_apply", "Watercolor",
                  "Applies the pigment densities of a `pigment_canvas` (turbulence, dispersion, "
                  "paper) to an image: C' = C(1 − (1 − C)(d − 1)); fused into the pass before it.",
                  kInputs, kOutputs, kParams, shaders::pigment_apply_glsl, 0);

const aq_node_desc* pigment_apply_node_desc() {
  return &kPigmentApplyNode;
}
