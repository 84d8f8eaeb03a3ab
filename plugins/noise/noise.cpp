// noise: a periodic, seeded procedural noise texture (Perlin, fBm, Gaussian or Worley) from the
// shared nodes/shaders/noise.glsl, for pigment turbulence and grain or anything else that wants
// a tileable noise image; a scanned texture can replace it through `read`. See README.md.
#include <aquarelle/plugin.hpp>

#include <algorithm>
#include <cmath>
#include <string>

#include "noise_shaders.h"

namespace {

constexpr aq_port_desc kOutputs[] = {aq::image_port("image", "noise value in rgb, alpha 1")};
enum Param { kType, kScale, kOctaves, kSeed, kRange, kWidth, kHeight };
constexpr aq_param_desc kParams[] = {
    aq::enum_param("type", "perlin|fbm|gaussian|worley", 1,
                   "gradient noise, its fractal sum, per-cell white Gaussian, or cellular F1"),
    aq::int_param("scale", 8, 1, 4096,
                  "lattice cells across the texture width (the period; a whole number)"),
    aq::int_param("octaves", 5, 1, 12, "fbm octaves, each twice the frequency, half the weight"),
    aq::int_param("seed", 0, 0, 16777216, "independent field per seed"),
    aq::enum_param("range", "unit|raw", 0,
                   "unit: perlin/fbm (v+1)/2, gaussian clamp(0.5+v/6), worley min(F1,1); raw: v"),
    aq::int_param("width", 0, 0, 16384, "output width in pixels; 0 = the graph's width"),
    aq::int_param("height", 0, 0, 16384, "output height in pixels; 0 = the graph's height")};

struct Noise {
  int process(aq::Context& ctx) {
    const int width = ctx.param_int(kWidth) > 0 ? int(ctx.param_int(kWidth)) : ctx.width();
    const int height = ctx.param_int(kHeight) > 0 ? int(ctx.param_int(kHeight)) : ctx.height();
    if (width < 1 || height < 1) {
      return ctx.fail("noise: output size " + std::to_string(width) + "x" + std::to_string(height) +
                      " is empty; set width and height, or the graph's");
    }
    // Cells stay square: the height gets the whole number of cells closest to the aspect.
    const double cells_x = double(ctx.param_int(kScale));
    const double cells_y = std::max(1.0, std::round(cells_x * height / width));

    aq_image out;
    if (!ctx.output(0, width, height, ctx.working_format(), &out)) return AQ_ERROR;
    GLuint program = ctx.program(shaders::noise_texture_frag);
    if (program == 0) return AQ_ERROR;
    glUseProgram(program);
    aq::set_vec2(program, "u_size", width, height);
    aq::set_vec2(program, "u_cells", cells_x, cells_y);
    aq::set_int(program, "u_type", int(ctx.param_enum(kType)));
    aq::set_int(program, "u_octaves", int(ctx.param_int(kOctaves)));
    aq::set_int(program, "u_seed", int(ctx.param_int(kSeed)));
    aq::set_int(program, "u_unit_range", ctx.param_enum(kRange) == 0 ? 1 : 0);
    const bool drawn = ctx.draw(out);
    glUseProgram(0);
    return drawn ? AQ_OK : AQ_ERROR;
  }
};

AQ_SOURCE_NODE(
    kNoiseNode, Noise, "noise", "Texture",
    "Periodic seeded noise texture: Perlin, fBm, Gaussian or Worley; sizes in texture units.", 0,
    kOutputs, kParams);

}  // namespace

AQ_PLUGIN("noise", "1.0", &kNoiseNode)
