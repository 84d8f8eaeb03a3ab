// bleed: MNPR / seed 002 colour bleeding. A strong Gaussian blur, applied where the control map
// asks, whose amount at a pixel is the largest bleed within the kernel, so colour runs past an
// object's border; a farther object of another id never runs into a nearer one (depth and id
// tested per tap), while parts of one object bleed together whatever their depth order.
//
//   control.r · amount, depth, id ──► key (one RGBA32F texel per pixel)
//   image, key ──► horizontal gated pass ──► colour_h, key_h (amount = max over the row taps)
//   colour_h, key_h, image ──► vertical gated pass ──► mix(image, blurred, amount)
//
// The two 1D passes define the operator (each gate compares a tap with the pixel it runs
// into, the vertical pass on the horizontal one's results); reference/bleed.h computes the
// same definition in double. Amount 0 at a pixel returns its texel unchanged (bit-exact).
#include <aquarelle/plugin.hpp>

#include <algorithm>
#include <cmath>
#include <string>

#include "bleed_shaders.h"

namespace {

enum Input : uint32_t { kImage, kControl, kDepth, kId };
constexpr aq_port_desc kInputs[] = {
    aq::image_port("image", "colour to bleed"),
    aq::image_port("control", "control map; red is the bleed amount [0, 1]"),
    aq::optional_image_port("depth",
                            "linear view depth (gbuffer.depth); unconnected: no depth test"),
    aq::optional_image_port("id", "object id (gbuffer.id); unconnected: one object")};
constexpr aq_port_desc kOutputs[] = {aq::image_port("image", "colour with bleeding")};
enum Param : uint32_t { kSigma, kReach, kAmount, kDepthBias };
constexpr aq_param_desc kParams[] = {
    aq::float_param("sigma", 20.0, 0.0, 200.0,
                    "Gaussian sigma in output pixels (the seed's 20); 0 passes the image through"),
    aq::float_param(
        "reach", 3.0, 0.25, 4.0,
        "kernel radius in sigmas (3: 99.7% of the Gaussian weight in each pass; the seed's "
        "21x21 at sigma 20 is 0.5)"),
    aq::float_param("amount", 1.0, 0.0, 1.0,
                    "multiplies the control map's bleed; 0 passes the image through"),
    aq::float_param("depth_bias", 0.05, 0.0, 100.0,
                    "world units a tap may lie behind the pixel and still run into it")};

struct Bleed {
  int process(aq::Context& ctx) {
    const aq_image in = ctx.input_image(kImage);
    const double sigma = ctx.param_float(kSigma) * ctx.render_scale();
    const double amount = ctx.param_float(kAmount);
    if (!(sigma > 0.0) || !(amount > 0.0)) return ctx.pass_through(0, kImage) ? AQ_OK : AQ_ERROR;
    const int radius = std::clamp(static_cast<int>(std::ceil(ctx.param_float(kReach) * sigma)), 1,
                                  std::max(in.width, in.height));
    aq_image out, key, colour_h, key_h;
    if (!ctx.output_like(0, in, &out) ||
        !ctx.scratch(in.width, in.height, AQ_FORMAT_RGBA32F, &key) ||
        !ctx.scratch(in.width, in.height, AQ_FORMAT_RGBA32F, &colour_h) ||
        !ctx.scratch(in.width, in.height, AQ_FORMAT_RGBA32F, &key_h)) {
      return AQ_ERROR;
    }
    const GLuint key_program = ctx.program(shaders::bleed_key_frag);
    const GLuint pass_program = ctx.program(shaders::bleed_pass_frag);
    if (key_program == 0 || pass_program == 0) return AQ_ERROR;

    glUseProgram(key_program);
    const aq_image control = ctx.input_image(kControl);
    aq::bind_texture(key_program, "u_control", 0, control);
    aq::bind_texture(key_program, "u_depth", 1,
                     ctx.connected(kDepth) ? ctx.input_image(kDepth) : control);
    aq::bind_texture(key_program, "u_id", 2, ctx.connected(kId) ? ctx.input_image(kId) : control);
    aq::set_int(key_program, "u_has_depth", ctx.connected(kDepth) ? 1 : 0);
    aq::set_int(key_program, "u_has_id", ctx.connected(kId) ? 1 : 0);
    aq::set_float(key_program, "u_amount", amount);
    if (!ctx.draw(key)) return AQ_ERROR;

    glUseProgram(pass_program);
    aq::set_int(pass_program, "u_radius", radius);
    aq::set_float(pass_program, "u_inv_two_sigma2", 1.0 / (2.0 * sigma * sigma));
    aq::set_float(pass_program, "u_depth_bias", ctx.param_float(kDepthBias));
    const aq_image horizontal[2] = {colour_h, key_h};
    aq::bind_texture(pass_program, "u_color", 0, in);
    aq::bind_texture(pass_program, "u_key", 1, key);
    aq::bind_texture(pass_program, "u_original", 2, in);
    glUniform2i(glGetUniformLocation(pass_program, "u_direction"), 1, 0);
    aq::set_int(pass_program, "u_final", 0);
    if (!ctx.bind_targets(horizontal, 2)) return AQ_ERROR;
    ctx.raw()->host->draw_fullscreen(ctx.raw()->host_data);

    aq::bind_texture(pass_program, "u_color", 0, colour_h);
    aq::bind_texture(pass_program, "u_key", 1, key_h);
    glUniform2i(glGetUniformLocation(pass_program, "u_direction"), 0, 1);
    aq::set_int(pass_program, "u_final", 1);
    const bool drawn = ctx.draw(out);
    aq::unbind_textures(3);
    return drawn ? AQ_OK : AQ_ERROR;
  }
};

}  // namespace

AQ_NODE(kBleedNode, Bleed, "bleed", "Watercolor",
        "MNPR colour bleeding: a strong Gaussian where the control map's red asks, its amount the "
        "largest bleed within the kernel so colour runs past borders; depth and id keep a "
        "farther object from running into a nearer one.",
        0, kInputs, kOutputs, kParams);
AQ_PLUGIN("bleed", "1.0", &kBleedNode)
