// paper_relief: seed 002's paper pass. The painted image sits on rough paper: the `paper` node's
// height field (Worley layered with FBM) gives normals by central differences, which light the
// image as a bump map; where the pigment is diluted (the dilution node's mask) the paper colour
// shows through:
//
//   image, mask ──► base = mix(image, paper_colour, show · mask)
//   paper height ──► N = normalize(−bump ∂h/∂x, −bump ∂h/∂y, 1) ──► s = max(N·L, 0) / L.z
//   ──► base · (1 + relief (s − 1))         (flat paper or relief 0: base exactly)
//
// The paper is read at the pixel under each image pixel (nearest; any size), borders clamp.
// Pointwise in the image: the host fuses it with the nodes around it (shaders/paper_relief.glsl).
#include <aquarelle/plugin.hpp>

#include <algorithm>
#include <cmath>
#include <string>

#include "paper_relief_shaders.h"

namespace {

enum Input : uint32_t { kImage, kPaper, kMask };
constexpr aq_port_desc kInputs[] = {
    aq::image_port("image", "the painted image"),
    aq::image_port("paper", "paper height in red (the `paper` node)"),
    aq::optional_image_port("mask",
                            "how much paper shows through, in red (dilution.dilution); "
                            "unconnected: none")};
constexpr aq_port_desc kOutputs[] = {aq::image_port("image", "the image on lit paper")};
enum Param : uint32_t { kLight, kBump, kRelief, kPaperColor, kShow };
constexpr aq_param_desc kParams[] = {
    aq::vec3_param("light", -0.5, 0.5, 0.7, -1, 1,
                   "direction towards the light in image space (x right, y up, z out of the "
                   "paper); z is kept above 0.05"),
    aq::float_param("bump", 4.0, 0.0, 100.0, "height-to-slope gain of the paper's normals"),
    aq::float_param("relief", 1.0, 0.0, 2.0, "how much the bump lighting shows; 0: none"),
    aq::color_param("paper_color", 0.96, 0.93, 0.85, "the paper's colour (linear)"),
    aq::float_param("show", 1.0, 0.0, 1.0, "how much the paper colour shows where mask is 1")};

struct PaperRelief {
  std::string fragment = aq::pointwise_fragment(shaders::paper_relief_glsl.text);

  int process(aq::Context& ctx) {
    const aq_image in = ctx.input_image(kImage);
    const bool mask = ctx.connected(kMask);
    if (ctx.param_float(kRelief) <= 0.0 && (!mask || ctx.param_float(kShow) <= 0.0)) {
      return ctx.pass_through(0, kImage) ? AQ_OK : AQ_ERROR;
    }
    aq_image out;
    if (!ctx.output_like(0, in, &out)) return AQ_ERROR;
    const GLuint program =
        ctx.program(aq_shader_source{"paper_relief.glsl", fragment.c_str(), nullptr});
    if (program == 0) return AQ_ERROR;
    glUseProgram(program);
    aq::bind_texture(program, "u_image", 0, in);
    aq::bind_texture(program, "u_paper", 1, ctx.input_image(kPaper));
    aq::bind_texture(program, "u_mask", 2, mask ? ctx.input_image(kMask) : in);
    set_uniforms(ctx, program, "u_");
    const bool drawn = ctx.draw(out);
    aq::unbind_textures(3);
    return drawn ? AQ_OK : AQ_ERROR;
  }

  // The uniforms of paper_relief.glsl but its samplers, named prefix + name (the host binds
  // paper and mask when it fuses this node's function, which it does only with both connected).
  int set_uniforms(aq::Context& ctx, GLuint program, const std::string& prefix) {
    const double* l = ctx.param_vec3(kLight);
    double light[3] = {l[0], l[1], std::max(l[2], 0.05)};
    const double length =
        std::sqrt(light[0] * light[0] + light[1] * light[1] + light[2] * light[2]);
    for (double& v : light) v /= length;
    aq::set_int(program, (prefix + "has_mask").c_str(), ctx.connected(kMask) ? 1 : 0);
    aq::set_vec3(program, (prefix + "light").c_str(), light);
    aq::set_vec3(program, (prefix + "paper_color").c_str(), ctx.param_vec3(kPaperColor));
    aq::set_float(program, (prefix + "bump").c_str(), ctx.param_float(kBump));
    aq::set_float(program, (prefix + "relief").c_str(), ctx.param_float(kRelief));
    aq::set_float(program, (prefix + "show").c_str(), ctx.param_float(kShow));
    return AQ_OK;
  }
};

}  // namespace

// Pointwise in the image (reach 1: the paper is read one pixel around), so the host runs it
// inside the pass of the node before it (an epilogue) or fused with the pointwise nodes after it.
AQ_POINTWISE_NODE(kPaperReliefNode, PaperRelief, "paper_relief", "Watercolor",
                  "Seed 002 paper: the painted image lit as a bump map by the paper height's "
                  "normals, the paper colour showing through diluted areas.",
                  kInputs, kOutputs, kParams, shaders::paper_relief_glsl, 1);
AQ_PLUGIN("paper_relief", "1.0", &kPaperReliefNode)
