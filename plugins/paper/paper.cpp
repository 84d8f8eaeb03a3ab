// paper: a procedural watercolour paper height field (Worley grain layered with fBm, as in
// seed 002), periodic and seeded, for `wobble`, `pigment` and paper shading; a scanned paper
// can replace it through `read`. See README.md.
#include <aquarelle/plugin.hpp>

#include <algorithm>
#include <cmath>
#include <string>

#include "paper_shaders.h"

namespace {

constexpr aq_port_desc kOutputs[] = {
    aq::image_port("image", "paper height in rgb (0.5 mean level, [0,1]), alpha 1"),
    aq::image_port("gradient",
                   "height change per texel in rg (central differences, clamped at the "
                   "border), RGBA32F: what wobble reads instead of differencing the height")};
enum Param { kGrainScale, kFiberScale, kOctaves, kFiberWeight, kRoughness, kSeed, kWidth, kHeight };
constexpr aq_param_desc kParams[] = {
    aq::int_param("grain_scale", 48, 1, 4096, "grain bumps (Worley cells) across the width"),
    aq::int_param("fiber_scale", 6, 1, 4096, "fBm lattice cells across the width"),
    aq::int_param("octaves", 5, 1, 12, "fBm octaves"),
    aq::float_param("fiber_weight", 0.35, 0.0, 1.0, "0: grain only, 1: fibres only"),
    aq::float_param("roughness", 1.0, 0.0, 1.0, "relief contrast; 0 is flat paper (0.5)"),
    aq::int_param("seed", 0, 0, 16777216, "independent paper per seed"),
    aq::int_param("width", 0, 0, 16384, "output width in pixels; 0 = the graph's width"),
    aq::int_param("height", 0, 0, 16384, "output height in pixels; 0 = the graph's height")};

// Whole numbers of cells per axis with (nearly) square cells, so the texture tiles.
void set_cells(GLuint program, const char* name, int64_t across_width, int width, int height) {
  const double x = double(across_width);
  aq::set_vec2(program, name, x, std::max(1.0, std::round(x * height / width)));
}

struct Paper {
  int process(aq::Context& ctx) {
    const int width = ctx.param_int(kWidth) > 0 ? int(ctx.param_int(kWidth)) : ctx.width();
    const int height = ctx.param_int(kHeight) > 0 ? int(ctx.param_int(kHeight)) : ctx.height();
    if (width < 1 || height < 1) {
      return ctx.fail("paper: output size " + std::to_string(width) + "x" + std::to_string(height) +
                      " is empty; set width and height, or the graph's");
    }
    aq_image out;
    if (!ctx.output(0, width, height, ctx.working_format(), &out)) return AQ_ERROR;
    // The host may store `image` in 8 bits when its readers say that is enough; the height is
    // then rendered at the working precision into a scratch image, and the gradient pass
    // differences that and copies it into `image` (a second target), so the gradient keeps
    // its precision and the costly height shader still runs once.
    aq_image height_for_gradient = out;
    if (out.format != ctx.working_format() &&
        !ctx.scratch(width, height, ctx.working_format(), &height_for_gradient)) {
      return AQ_ERROR;
    }
    GLuint program = ctx.program(shaders::paper_height_frag);
    if (program == 0) return AQ_ERROR;
    glUseProgram(program);
    aq::set_vec2(program, "u_size", width, height);
    set_cells(program, "u_grain_cells", ctx.param_int(kGrainScale), width, height);
    set_cells(program, "u_fiber_cells", ctx.param_int(kFiberScale), width, height);
    aq::set_int(program, "u_octaves", int(ctx.param_int(kOctaves)));
    aq::set_float(program, "u_fiber_weight", ctx.param_float(kFiberWeight));
    aq::set_float(program, "u_roughness", ctx.param_float(kRoughness));
    aq::set_int(program, "u_seed", int(ctx.param_int(kSeed)));
    if (!ctx.draw(height_for_gradient)) return AQ_ERROR;
    const bool copy_height = height_for_gradient.texture != out.texture;

    // The gradient once here (the paper is static, so cached) rather than four reads per pixel
    // in every frame's wobble.
    aq_image gradient;
    if (!ctx.output(1, width, height, AQ_FORMAT_RGBA32F, &gradient)) return AQ_ERROR;
    const std::string text = std::string("#define AQ_PAPER_COPY_HEIGHT ") +
                             (copy_height ? "1" : "0") + "\n" + shaders::paper_gradient_frag.text;
    GLuint differences =
        ctx.program(aq_shader_source{shaders::paper_gradient_frag.name, text.c_str(), nullptr});
    if (differences == 0) return AQ_ERROR;
    glUseProgram(differences);
    aq::bind_texture(differences, "u_height", 0, height_for_gradient);
    const aq_image targets[2] = {gradient, out};
    const bool drawn = ctx.bind_targets(targets, copy_height ? 2 : 1);
    if (drawn) ctx.raw()->host->draw_fullscreen(ctx.raw()->host_data);
    aq::unbind_textures(1);
    glUseProgram(0);
    return drawn ? AQ_OK : AQ_ERROR;
  }
};

AQ_SOURCE_NODE(
    kPaperNode, Paper, "paper", "Texture",
    "Procedural watercolour paper height: Worley grain layered with fBm; periodic, seeded.", 0,
    kOutputs, kParams);

}  // namespace

AQ_PLUGIN("paper", "1.0", &kPaperNode)
