// bleed: MNPR / seed 002 colour bleeding. A strong Gaussian blur, applied where the control map
// asks, whose amount at a pixel is the largest bleed within the kernel, so colour runs past an
// object's border; a farther object of another id never runs into a nearer one (depth and id
// tested per tap), while parts of one object bleed together whatever their depth order.
//
//   control.r · amount, depth, id ──► key (one RGBA32F texel per pixel)
//   image, key ──► horizontal gated pass ──► colour_h, key_h (amount = max over the row taps)
//   colour_h, key_h, image ──► vertical gated pass ──► mix(image, blurred, amount)
//
// By default the two passes run on cells of up to 4×4 pixels (σ / cell; never under 2 cells):
// the nearest pixel of a cell represents it, the cell's colour is the mean of the pixels that
// may run into it, and the full-size mix takes the four nearest cells that may run into the
// pixel (resolution 1: every pixel, the exact operator; the bench states the cells' error).
//
// The two 1D passes define the operator (each gate compares a tap with the pixel it runs
// into, the vertical pass on the horizontal one's results); reference/bleed.h computes the
// same definition in double. Amount 0 at a pixel returns its texel unchanged (bit-exact).
#include <aquarelle/plugin.hpp>
#include <aquarelle/sdk/gl_raii.hpp>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

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
enum Param : uint32_t { kSigma, kReach, kAmount, kDepthBias, kResolution, kExtrude };
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
                    "world units a tap may lie behind the pixel and still run into it"),
    aq::int_param("resolution", 4, 1, 16,
                  "largest cell (output pixels per side) the blur runs on; the cell keeps "
                  "sigma at 2 cells or more; 1: every pixel, exact"),
    aq::float_param("extrude", 0.0, 0.0, 32.0,
                    "bleed extrusion: output pixels the bleeding geometry is pushed past its "
                    "silhouette at bleed 1 (times the bleed), before the blur; 0: none")};

// The gated 1D passes: horizontal into (colour_h, key_h), vertical into `targets` (the output
// with `final`, else a colour and key pair). Program and uniforms are set by the caller.
bool gated_passes(aq::Context& ctx, GLuint program, const aq_image& color, const aq_image& key,
                  const aq_image& original, const aq_image (&horizontal)[2],
                  const aq_image* targets, uint32_t target_count, bool final,
                  const aq::Region& rows = aq::Region::everything(),
                  const aq::Region& columns = aq::Region::everything()) {
  aq::bind_texture(program, "u_color", 0, color);
  aq::bind_texture(program, "u_key", 1, key);
  aq::bind_texture(program, "u_original", 2, original);
  glUniform2i(glGetUniformLocation(program, "u_direction"), 1, 0);
  aq::set_int(program, "u_final", 0);
  if (!ctx.bind_targets(horizontal, 2)) return false;
  ctx.set_draw_region(rows);
  ctx.raw()->host->draw_fullscreen(ctx.raw()->host_data);
  aq::bind_texture(program, "u_color", 0, horizontal[0]);
  aq::bind_texture(program, "u_key", 1, horizontal[1]);
  glUniform2i(glGetUniformLocation(program, "u_direction"), 0, 1);
  aq::set_int(program, "u_final", final ? 1 : 0);
  if (!ctx.bind_targets(targets, target_count)) return false;
  ctx.set_draw_region(columns);
  ctx.raw()->host->draw_fullscreen(ctx.raw()->host_data);
  return true;
}

struct Bleed {
  int process(aq::Context& ctx) {
    const aq_image in = ctx.input_image(kImage);
    const double sigma = ctx.param_float(kSigma) * ctx.render_scale();
    const double amount = ctx.param_float(kAmount);
    if (!(sigma > 0.0) || !(amount > 0.0)) return ctx.pass_through(0, kImage) ? AQ_OK : AQ_ERROR;
    // The blur runs on cells of `cell`² pixels, as large as asked but keeping σ >= 2 cells.
    const int asked =
        std::max(1, static_cast<int>(std::lround(ctx.param_int(kResolution) * ctx.render_scale())));
    const int cell = std::clamp(static_cast<int>(std::floor(sigma / 2.0)), 1, asked);
    aq_image out;
    if (!ctx.output_like(0, in, &out)) return AQ_ERROR;
    damage_ = damaged(ctx, in, out, sigma, cell);
    const bool drawn = cell == 1 ? exact(ctx, in, sigma, out) : on_cells(ctx, in, sigma, cell, out);
    ctx.set_draw_region(aq::Region::everything());
    aq::unbind_textures(9);
    return drawn && ctx.set_output_damage(0, damage_) ? AQ_OK : AQ_ERROR;
  }

 private:
  // Damage tracking: the passes on cells (or the first exact pass) run whole each frame, from
  // the same inputs the same values; only the last pass, the full-size one, is limited to the
  // pixels that can reach a changed input texel: the cell, the extrusion's reach, the kernel's
  // and the two cells the upsampling reads, all in pixels.
  aq::Region damaged(aq::Context& ctx, const aq_image& in, const aq_image& out, double sigma,
                     int cell) {
    changed_ = aq::Region::everything();
    if (!ctx.output_kept(0)) return aq::Region::everything();
    aq::Region changed = ctx.input_damage(kImage);
    for (uint32_t input : {kControl, kDepth, kId}) {
      if (!ctx.connected(input)) continue;
      const aq_image image = ctx.input_image(input);
      if (image.width != in.width || image.height != in.height) return aq::Region::everything();
      changed.add(ctx.input_damage(input));
    }
    changed_ = changed;
    const int length = std::max((in.width + cell - 1) / cell, (in.height + cell - 1) / cell);
    const int radius =
        std::clamp(static_cast<int>(std::ceil(ctx.param_float(kReach) * sigma / cell)), 1,
                   std::max(length, 1));
    const int extruded = static_cast<int>(std::ceil(extrude_pixels(ctx) / cell));
    const int reach = cell * (radius + extruded + 3);
    return changed.dilated(reach, reach, out.width, out.height).for_drawing();
  }

  aq::Region damage_ = aq::Region::everything();
  aq::Region changed_ = aq::Region::everything();  // the inputs' changed pixels (or all)
  // The cells' textures (down, extruded, horizontal, blurred: colour and key each), the node's
  // own between calls, so that only the cells a changed pixel can reach are drawn again.
  aq::gl::KeptTexture kept_cells_[8];
  bool cells_valid_ = false;  // they hold the last call's cells

  // Kept cell texture `k` for w x h cells; `*all_kept` false when one was (re)made.
  aq_image kept_cell(aq::Context& ctx, int k, int w, int h, bool* all_kept) {
    bool kept = false;
    const GLuint name = kept_cells_[k].get(ctx.raw()->gl_generation, w, h, GL_RGBA32F, &kept);
    if (!kept) {  // sampled as the pool's textures are: bilinear, clamped at the edges
      glTextureParameteri(name, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
      glTextureParameteri(name, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
      glTextureParameteri(name, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
      glTextureParameteri(name, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    }
    *all_kept = *all_kept && kept;
    return aq_image{name, w, h, AQ_FORMAT_RGBA32F};
  }

  // The cells of `cell`² pixels holding the pixels of `pixels`.
  static aq::Region cells_of(const aq::Region& pixels, int cell, int w, int h) {
    if (pixels.all()) return pixels;
    std::vector<aq::PixelRect> rects;
    for (const aq::PixelRect& r : pixels.rects()) {
      rects.push_back(aq::PixelRect{r.x0 / cell, r.y0 / cell, std::min((r.x1 + cell - 1) / cell, w),
                                    std::min((r.y1 + cell - 1) / cell, h)});
    }
    aq::Region cells;
    cells.add(rects);
    return cells;
  }

  // The node's inputs as bleed_inputs.glsl reads them (units 4 to 6).
  static void bind_inputs(aq::Context& ctx, GLuint program) {
    const aq_image control = ctx.input_image(kControl);
    aq::bind_texture(program, "u_control", 4, control);
    aq::bind_texture(program, "u_depth", 5,
                     ctx.connected(kDepth) ? ctx.input_image(kDepth) : control);
    aq::bind_texture(program, "u_id", 6, ctx.connected(kId) ? ctx.input_image(kId) : control);
    aq::set_int(program, "u_has_depth", ctx.connected(kDepth) ? 1 : 0);
    aq::set_int(program, "u_has_id", ctx.connected(kId) ? 1 : 0);
    aq::set_float(program, "u_amount", ctx.param_float(kAmount));
  }

  // A program of `fragment` with bleed_inputs.glsl before it.
  static GLuint with_inputs(aq::Context& ctx, const aq_shader_source& fragment) {
    const std::string text =
        std::string(shaders::bleed_inputs_glsl.text) + "\n#line 1\n" + fragment.text;
    return ctx.program(aq_shader_source{fragment.name, text.c_str(), nullptr});
  }

  // (bleed · amount, depth, id) per pixel, so each tap of the exact passes reads two textures
  // instead of four.
  static bool make_key(aq::Context& ctx, const aq_image& key) {
    const GLuint program = with_inputs(ctx, shaders::bleed_key_frag);
    if (program == 0) return false;
    glUseProgram(program);
    bind_inputs(ctx, program);
    return ctx.draw(key);
  }

  // The extrusion's reach at bleed 1, in working pixels.
  static double extrude_pixels(aq::Context& ctx) {
    return std::max(ctx.param_float(kExtrude), 0.0) * ctx.render_scale();
  }

  // Pushes the bleeding geometry out (bleed_extrude.frag) on texels of `spacing` pixels:
  // (colour, key) into targets[0..1].
  static bool extrude(aq::Context& ctx, const aq_image& colour, const aq_image& key, int spacing,
                      const aq_image (&targets)[2]) {
    const GLuint program = ctx.program(shaders::bleed_extrude_frag);
    if (program == 0) return false;
    const double pixels = extrude_pixels(ctx);
    glUseProgram(program);
    aq::bind_texture(program, "u_color", 0, colour);
    aq::bind_texture(program, "u_key", 1, key);
    aq::set_float(program, "u_spacing", spacing);
    aq::set_float(program, "u_extrude", pixels);
    aq::set_int(program, "u_radius", static_cast<int>(std::ceil(pixels / spacing)));
    if (!ctx.bind_targets(targets, 2)) return false;
    ctx.raw()->host->draw_fullscreen(ctx.raw()->host_data);
    return true;
  }

  static GLuint pass_program(aq::Context& ctx, double sigma, int length) {
    const GLuint program = ctx.program(shaders::bleed_pass_frag);
    if (program == 0) return 0;
    const int radius = std::clamp(static_cast<int>(std::ceil(ctx.param_float(kReach) * sigma)), 1,
                                  std::max(length, 1));
    glUseProgram(program);
    aq::set_int(program, "u_radius", radius);
    aq::set_float(program, "u_inv_two_sigma2", 1.0 / (2.0 * sigma * sigma));
    aq::set_float(program, "u_depth_bias", ctx.param_float(kDepthBias));
    return program;
  }

  // The definition itself, every pixel a tap (reference/bleed.h).
  bool exact(aq::Context& ctx, const aq_image& in, double sigma, const aq_image& out) {
    aq_image key, colour_h, key_h;  // key: the packed inputs, then extruded when asked
    if (!ctx.scratch(in.width, in.height, AQ_FORMAT_RGBA32F, &key) || !make_key(ctx, key) ||
        !ctx.scratch(in.width, in.height, AQ_FORMAT_RGBA32F, &colour_h) ||
        !ctx.scratch(in.width, in.height, AQ_FORMAT_RGBA32F, &key_h)) {
      return false;
    }
    aq_image colour = in;
    if (extrude_pixels(ctx) > 0.0) {
      aq_image extruded[2];
      for (aq_image& image : extruded)
        if (!ctx.scratch(in.width, in.height, AQ_FORMAT_RGBA32F, &image)) return false;
      if (!extrude(ctx, in, key, 1, extruded)) return false;
      colour = extruded[0];
      key = extruded[1];
    }
    const GLuint program = pass_program(ctx, sigma, std::max(in.width, in.height));
    return program != 0 && gated_passes(ctx, program, colour, key, colour, {colour_h, key_h}, &out,
                                        1, /*final=*/true, aq::Region::everything(), damage_);
  }

  // The same passes on cells of cell² pixels (σ / cell), then the cells brought back by the
  // gate (bleed_down.frag, bleed_up.frag): a wide Gaussian is smooth at the cell's scale. Both
  // read the node's inputs directly: no full-size key.
  bool on_cells(aq::Context& ctx, const aq_image& in, double sigma, int cell, const aq_image& out) {
    const int w = (in.width + cell - 1) / cell, h = (in.height + cell - 1) / cell;
    bool all_kept = true;
    aq_image cells[2], horizontal[2], blurred[2], extruded[2];
    for (int k = 0; k < 2; ++k) {
      cells[k] = kept_cell(ctx, k, w, h, &all_kept);
      extruded[k] = kept_cell(ctx, 2 + k, w, h, &all_kept);
      horizontal[k] = kept_cell(ctx, 4 + k, w, h, &all_kept);
      blurred[k] = kept_cell(ctx, 6 + k, w, h, &all_kept);
    }
    // Damage tracking on the cells: a down cell changes with its own pixels, an extruded one
    // within the extrusion's reach of those, a gated pass's within its radius along its axis
    // (and one more for the block flag); the rest keep what the last call drew.
    const bool extruding = extrude_pixels(ctx) > 0.0;
    const int length = std::max(w, h);
    const int radius =
        std::clamp(static_cast<int>(std::ceil(ctx.param_float(kReach) * sigma / cell)), 1,
                   std::max(length, 1));
    const int reach = extruding ? static_cast<int>(std::ceil(extrude_pixels(ctx) / cell)) : 0;
    const aq::Region down_cells = all_kept && cells_valid_
                                      ? cells_of(changed_, cell, w, h).for_drawing()
                                      : aq::Region::everything();
    const aq::Region extruded_cells = down_cells.dilated(reach, reach, w, h).for_drawing();
    const aq::Region row_cells = extruded_cells.dilated(radius + 1, 1, w, h).for_drawing();
    const aq::Region column_cells = row_cells.dilated(1, radius + 1, w, h).for_drawing();
    cells_valid_ = false;
    const GLuint down = with_inputs(ctx, shaders::bleed_down_frag);
    const GLuint up = with_inputs(ctx, shaders::bleed_up_frag);
    if (down == 0 || up == 0) return false;
    const float bias = static_cast<float>(ctx.param_float(kDepthBias));
    glUseProgram(down);
    aq::bind_texture(down, "u_color", 0, in);
    bind_inputs(ctx, down);
    aq::set_int(down, "u_cell", cell);
    aq::set_float(down, "u_depth_bias", bias);
    if (!ctx.bind_targets(cells, 2)) return false;
    ctx.set_draw_region(down_cells);
    ctx.raw()->host->draw_fullscreen(ctx.raw()->host_data);
    if (extruding) {
      ctx.set_draw_region(extruded_cells);
      if (!extrude(ctx, cells[0], cells[1], cell, extruded)) return false;
    } else {
      extruded[0] = cells[0];
      extruded[1] = cells[1];
    }
    const GLuint program = pass_program(ctx, sigma / cell, std::max(w, h));
    if (program == 0 ||
        !gated_passes(ctx, program, extruded[0], extruded[1], extruded[0],
                      {horizontal[0], horizontal[1]}, blurred, 2, false, row_cells, column_cells)) {
      return false;
    }
    cells_valid_ = true;
    glUseProgram(up);
    aq::bind_texture(up, "u_original", 0, in);
    bind_inputs(ctx, up);
    aq::bind_texture(up, "u_cell_color", 2, blurred[0]);
    aq::bind_texture(up, "u_cell_key", 3, blurred[1]);
    aq::set_int(up, "u_cell", cell);
    aq::set_float(up, "u_depth_bias", bias);
    aq::set_int(up, "u_extruded", extruding ? 1 : 0);
    aq::bind_texture(up, "u_cell_source", 7, extruded[0]);
    aq::bind_texture(up, "u_cell_source_key", 8, extruded[1]);
    ctx.set_draw_region(damage_);
    return ctx.draw(out);
  }
};

}  // namespace

AQ_NODE(kBleedNode, Bleed, "bleed", "Watercolor",
        "MNPR colour bleeding: a strong Gaussian where the control map's red asks, its amount the "
        "largest bleed within the kernel so colour runs past borders; depth and id keep a "
        "farther object from running into a nearer one.",
        0, kInputs, kOutputs, kParams);
AQ_PLUGIN("bleed", "1.0", &kBleedNode)
