// tint: mixes the image towards a constant colour, the last step of the seed's underwater pass
// (Paré-Vogt & Chaid §5): out = mix(colour, tint, amount). A template for pointwise nodes.
#include <aquarelle/plugin.hpp>

#include <string>

#include "tint_shaders.h"

namespace {

constexpr aq_port_desc kInputs[] = {aq::image_port("image", "colour to tint")};
constexpr aq_port_desc kOutputs[] = {aq::image_port("image", "tinted colour")};
enum Param { kAmount, kTint };
constexpr aq_param_desc kParams[] = {
    aq::float_param("amount", 0.2, 0.0, 1.0, "mix factor: 0 keeps the image, 1 is flat tint"),
    aq::color_param("tint", 0.0, 0.07, 0.1, "water colour (linear)")};

struct Tint {
  std::string fragment = aq::pointwise_fragment(shaders::tint_glsl.text);

  int process(aq::Context& ctx) {
    aq_image in = ctx.input_image(0);
    if (ctx.param_float(kAmount) <= 0.0) return ctx.pass_through(0, 0) ? AQ_OK : AQ_ERROR;
    aq_image out;
    if (!ctx.output_like(0, in, &out)) return AQ_ERROR;
    GLuint program = ctx.program(aq_shader_source{"tint.glsl", fragment.c_str(), nullptr});
    if (program == 0) return AQ_ERROR;
    glUseProgram(program);
    aq::bind_texture(program, "u_image", 0, in);
    set_uniforms(ctx, program, "u_");
    bool drawn = ctx.draw(out);
    aq::unbind_textures(1);
    return drawn ? AQ_OK : AQ_ERROR;
  }

  // The uniforms of tint.glsl, named prefix + name (the host fuses this node's function).
  int set_uniforms(aq::Context& ctx, GLuint program, const std::string& prefix) {
    aq::set_vec3(program, (prefix + "tint").c_str(), ctx.param_vec3(kTint));
    aq::set_float(program, (prefix + "amount").c_str(), ctx.param_float(kAmount));
    return AQ_OK;
  }
};

}  // namespace

AQ_POINTWISE_NODE(kTintNode, Tint, "tint", "Color",
                  "Mixes the image towards a water colour: mix(colour, tint, amount).", kInputs,
                  kOutputs, kParams, shaders::tint_glsl, 0);
AQ_PLUGIN("tint", "1.0", &kTintNode)
