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
#include <aquarelle/plugin.hpp>

#include <cmath>

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
  int process(aq::Context& ctx) {
    const aq_image in = ctx.input_image(kImage);
    const bool mask = ctx.connected(kMask);
    if (ctx.param_float(kRelief) <= 0.0 && (!mask || ctx.param_float(kShow) <= 0.0)) {
      return ctx.pass_through(0, kImage) ? AQ_OK : AQ_ERROR;
    }
    const double* l = ctx.param_vec3(kLight);
    double light[3] = {l[0], l[1], std::max(l[2], 0.05)};
    const double length =
        std::sqrt(light[0] * light[0] + light[1] * light[1] + light[2] * light[2]);
    for (double& v : light) v /= length;
    aq_image out;
    if (!ctx.output_like(0, in, &out)) return AQ_ERROR;
    const GLuint program = ctx.program(shaders::paper_relief_frag);
    if (program == 0) return AQ_ERROR;
    glUseProgram(program);
    aq::bind_texture(program, "u_image", 0, in);
    aq::bind_texture(program, "u_paper", 1, ctx.input_image(kPaper));
    aq::bind_texture(program, "u_mask", 2, mask ? ctx.input_image(kMask) : in);
    aq::set_int(program, "u_has_mask", mask ? 1 : 0);
    aq::set_vec3(program, "u_light", light);
    aq::set_vec3(program, "u_paper_color", ctx.param_vec3(kPaperColor));
    aq::set_float(program, "u_bump", ctx.param_float(kBump));
    aq::set_float(program, "u_relief", ctx.param_float(kRelief));
    aq::set_float(program, "u_show", ctx.param_float(kShow));
    const bool drawn = ctx.draw(out);
    aq::unbind_textures(3);
    return drawn ? AQ_OK : AQ_ERROR;
  }
};

}  // namespace

AQ_NODE(kPaperReliefNode, PaperRelief, "paper_relief", "Watercolor",
        "Seed 002 paper: the painted image lit as a bump map by the paper height's normals, the "
        "paper colour showing through diluted areas.",
        0, kInputs, kOutputs, kParams);
AQ_PLUGIN("paper_relief", "1.0", &kPaperReliefNode)
