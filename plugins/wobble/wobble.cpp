// wobble: paper wobble (seed §3.4). Shifts every lookup of `image` by the gradient of a paper
// height field times `strength`. The paper is the optional `paper` input (height in red,
// stretched over the image) or, when unconnected, a procedural paper rendered first into a
// scratch texture:
//
//   [paper input] ─────────────────────────┐
//   procedural_paper.frag ──► scratch ─────┴──► wobble.frag(image, paper) ──► image
#include <aquarelle/plugin.hpp>
#include <aquarelle/sdk/blocks.hpp>
#include <aquarelle/sdk/region.hpp>

#include <algorithm>
#include <cmath>
#include <string>

#include "wobble_shaders.h"

namespace {

constexpr aq_port_desc kInputs[] = {
    // AQ_PORT_HDR8: an encoded image is decoded texel by texel before the bilinear blend.
    aq::image_port("image", "colour to displace", AQ_PORT_HDR8 | AQ_PORT_BLOCKS),
    // Heights in [0, 1] differenced over two paper pixels: 8 bits move the displacement by at
    // most strength/510 paper pixels (README), so the host may store the paper as RGBA8.
    aq_port_desc{"paper", AQ_PORT_IMAGE, AQ_PORT_OPTIONAL | AQ_PORT_8BIT_ENOUGH,
                 "paper height in the red channel, stretched over the image; "
                 "unconnected: a procedural paper"},
    aq::optional_image_port("gradient",
                            "the paper's `gradient` output (with `paper` connected): read once "
                            "per pixel instead of differencing the height with four reads")};
// AQ_PORT_HDR8: written encoded when every reader decodes it; AQ_PORT_BLOCKS: in 2 x 2 blocks
// when every reader takes them. With an epilogue, the output is the fused chain's (in
// graphs/underwater.json edge and pigment_apply, read by blur's rows pass in blocks).
constexpr aq_port_desc kOutputs[] = {
    aq::image_port("image", "displaced colour", AQ_PORT_HDR8 | AQ_PORT_BLOCKS)};
enum Input : uint32_t { kImage, kPaper, kGradient };
enum Param : uint32_t { kStrength, kPaperResolution, kGrain, kSeed };
constexpr aq_param_desc kParams[] = {
    aq::float_param("strength", 8.0, 0.0, 64.0,
                    "displacement in paper pixels per unit of height slope (height change per "
                    "paper pixel); 0 passes the image through"),
    aq::int_param("paper_resolution", 512, 8, 8192,
                  "procedural paper only: paper pixels across the image height (the width follows "
                  "the image's aspect)"),
    aq::float_param("grain", 6.0, 1.0, 256.0,
                    "procedural paper only: size of the paper's cells in paper pixels"),
    aq::int_param("seed", 0, 0, 1 << 20, "procedural paper only: which paper")};

struct Wobble {
  int process(aq::Context& ctx) {
    const aq_image in = ctx.input_image(kImage);
    const double strength = ctx.param_float(kStrength);
    aq_image out;
    if (!ctx.output_like(0, in, &out)) return AQ_ERROR;
    // Unmoved, the image passes through unless the input or the output is in 2 x 2 blocks
    // (its readers take the other): it is then drawn out.
    const bool blocks = aq::in_blocks(in);
    if (strength == 0.0 && !blocks && !aq::in_blocks(out))
      return ctx.pass_through(0, kImage) ? AQ_OK : AQ_ERROR;
    aq_image paper = ctx.input_image(kPaper);
    if (!ctx.connected(kPaper) && !render_procedural_paper(ctx, in, &paper)) return AQ_ERROR;

    // The precomputed gradient only stands for the paper it was computed from (same size).
    const bool precomputed = ctx.connected(kPaper) && ctx.connected(kGradient) &&
                             ctx.input_image(kGradient).width == paper.width &&
                             ctx.input_image(kGradient).height == paper.height;
    const std::string text =
        std::string("#define AQ_WOBBLE_GRADIENT ") + (precomputed ? "1" : "0") +
        "\n#define AQ_WOBBLE_DECODE_HDR8 " + (in.format == AQ_FORMAT_RGBA8_HDR ? "1" : "0") +
        "\n#define AQ_WOBBLE_ENCODE_HDR8 " + (out.format == AQ_FORMAT_RGBA8_HDR ? "1" : "0") +
        "\n#define AQ_WOBBLE_BLOCKS " + (blocks ? "1" : "0") + "\n#define AQ_WOBBLE_OUT_BLOCKS " +
        (aq::in_blocks(out) ? "1" : "0") + "\n" + shaders::wobble_frag.text;
    const GLuint program =
        ctx.program(aq_shader_source{shaders::wobble_frag.name, text.c_str(), nullptr});
    if (program == 0) return AQ_ERROR;
    glUseProgram(program);
    aq::set_vec2(program, "u_out_size", out.width, out.height);
    if (blocks) {
      aq::bind_blocks(program, in, in);
    } else {
      aq::bind_texture(program, "u_image", 0, in);
    }
    aq::bind_texture(program, "u_paper", 1, precomputed ? ctx.input_image(kGradient) : paper);
    aq::set_vec2(program, "u_paper_size", paper.width, paper.height);
    // The displacement is strength·h'/P² in uv for a paper of P pixels across (see the
    // shader), so a proxy render whose paper shrank with the working size (P·scale) needs
    // strength·scale² to move the image as far as the full-size render does.
    const double paper_scale = paper.width == ctx.width() ? ctx.render_scale() : 1.0;
    const double shift = strength * paper_scale * paper_scale;
    aq::set_float(program, "u_strength", shift);
    // Damage tracking: with the output kept, only pixels whose lookup can reach a changed pixel
    // of the image (the shift is at most shift/paper pixels of uv with the slope clamped to 1,
    // one more pixel for the bilinear blend), or whose paper or epilogue changed, are redrawn.
    aq::Region damage = aq::Region::everything();
    if (ctx.output_kept(0) && in.width == out.width && in.height == out.height) {
      const int reach_x = static_cast<int>(std::ceil(shift * out.width / paper.width)) + 1;
      const int reach_y = static_cast<int>(std::ceil(shift * out.height / paper.height)) + 1;
      damage = ctx.input_damage(kImage).dilated(reach_x, reach_y, out.width, out.height);
      const uint32_t paper_port = precomputed ? kGradient : kPaper;
      if (ctx.connected(paper_port)) {
        const aq_image read = ctx.input_image(paper_port);
        const aq::Region changed = ctx.input_damage(paper_port);
        const bool same_pixels = read.width == out.width && read.height == out.height;
        // The gradient is read at the pixel; the height four reads around it (one paper pixel).
        damage.add(
            same_pixels || changed.empty()
                ? changed.dilated(precomputed ? 0 : 1, precomputed ? 0 : 1, out.width, out.height)
                : aq::Region::everything());
      }
      damage.add(ctx.epilogue_damage());
    }
    const aq::Region region = aq::in_blocks(out) ? aq::blocks_of(damage) : damage;
    if (!ctx.set_draw_region(region.for_drawing())) damage = aq::Region::everything();
    // Drawn even when nothing changed: an empty region draws nothing, but the host learns that
    // the draw applies the epilogue (else it would run the fused nodes as a pass of their own).
    const bool drawn = ctx.draw(out);
    aq::unbind_textures(2);
    return drawn && ctx.set_output_damage(0, damage) ? AQ_OK : AQ_ERROR;
  }

  // The procedural paper is `paper_resolution` lines high and as wide as the image's aspect
  // asks, so its pixels (the unit of `strength` and `grain`) cover the same part of the image at
  // any output resolution.
  static bool render_procedural_paper(aq::Context& ctx, const aq_image& in, aq_image* paper) {
    const int lines = static_cast<int>(ctx.param_int(kPaperResolution));
    const double aspect = static_cast<double>(in.width) / static_cast<double>(in.height);
    const int columns = std::max(1, static_cast<int>(std::lround(lines * aspect)));
    if (!ctx.scratch(columns, lines, ctx.working_format(), paper)) return false;
    const GLuint program = ctx.program(shaders::procedural_paper_frag);
    if (program == 0) return false;
    glUseProgram(program);
    aq::set_vec2(program, "u_paper_size", columns, lines);
    aq::set_float(program, "u_grain", ctx.param_float(kGrain));
    // Each seed moves the paper by a different whole number of cells; offsets stay below 4096
    // cells so single-precision coordinates keep their sub-cell detail.
    const double seed = static_cast<double>(ctx.param_int(kSeed));
    aq::set_vec2(program, "u_seed_offset", std::fmod(seed * 113.0, 4096.0),
                 std::fmod(seed * 71.0, 4096.0));
    const bool drawn = ctx.draw(*paper);
    glUseProgram(0);
    return drawn;
  }
};

}  // namespace

AQ_NODE(kWobbleNode, Wobble, "wobble", "Watercolor",
        "Paper wobble: shifts each lookup by the paper height's gradient times a strength "
        "(in paper pixels, the same at every resolution).",
        AQ_NODE_EPILOGUE, kInputs, kOutputs, kParams);
AQ_PLUGIN("wobble", "1.0", &kWobbleNode)
