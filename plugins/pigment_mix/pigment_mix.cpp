// pigment_mix: mixes two images as paint, not as light (seed 004's CMYK interpolation, and
// Kubelka–Munk two-constant mixing after Curtis et al. 1997), or as light for comparison:
//
//   a ─┐
//      ├─► mix(a.rgb, b.rgb, factor · b.a) in `mode` ─► image   (alpha from a)
//   b ─┘
//
// The maths is the SDK's shared nodes/shaders/pigment.glsl, which the layered node uses for its
// colour interpolation and glazing too; README.md has it with its sources.
#include <aquarelle/plugin.hpp>

#include <string>

#include "pigment_mix_shaders.h"

namespace {

constexpr aq_port_desc kInputs[] = {
    aq::image_port("a", "first colour (and the output's alpha)"),
    aq::image_port("b", "second colour; its alpha scales the factor (sampled if another size)")};
constexpr aq_port_desc kOutputs[] = {aq::image_port("image", "mixed colour")};
enum Param { kMode, kFactor };
constexpr aq_param_desc kParams[] = {
    aq::enum_param("mode", "rgb|cmyk|kubelka_munk", 2,
                   "rgb: additive lerp (light); cmyk: the seed's lerp in CMYK; kubelka_munk: "
                   "two-constant pigment mixing (blue and yellow make green)"),
    aq::float_param("factor", 0.5, 0.0, 1.0, "concentration of b in the mixture")};

struct PigmentMix {
  std::string text;

  int process(aq::Context& ctx) {
    const aq_image a = ctx.input_image(0);
    aq_image out;
    if (!ctx.output_like(0, a, &out)) return AQ_ERROR;
    text = "#define AQ_PIGMENT_MODE " + std::to_string(ctx.param_enum(kMode)) + "\n" +
           shaders::pigment_mix_frag.text;
    const GLuint program = ctx.program(aq_shader_source{"pigment_mix.frag", text.c_str(), nullptr});
    if (program == 0) return AQ_ERROR;
    glUseProgram(program);
    aq::bind_texture(program, "u_a", 0, a);
    aq::bind_texture(program, "u_b", 1, ctx.input_image(1));
    aq::set_float(program, "u_factor", ctx.param_float(kFactor));
    const bool drawn = ctx.draw(out);
    aq::unbind_textures(2);
    return drawn ? AQ_OK : AQ_ERROR;
  }
};

}  // namespace

AQ_NODE(kPigmentMixNode, PigmentMix, "pigment_mix", "Color",
        "Mixes two images as pigments (CMYK or Kubelka-Munk) or as light (rgb).", 0, kInputs,
        kOutputs, kParams);
AQ_PLUGIN("pigment_mix", "1.0", &kPigmentMixNode)
