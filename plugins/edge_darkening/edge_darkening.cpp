// edge_darkening: MNPR / seed 002 edge darkening from the difference between an image and its
// Gaussian blur (the seed: 11×11, σ = 3). Near an edge the blur differs from the image, so
// raising each channel to the power 1 + k·d darkens it there and leaves flat areas alone:
//
//   source (or image) ──► aq::gaussian::blur σ ──► d = max_rgb |blur − source|
//   control (optional): k = strength · (g edge amount + grazing · b grazing angle)
//   e = e_max (1 − exp(−k d / e_max))   (saturates: corners and thin geometry never turn black)
//   image ──► C · min(C, 1)^e ──► image          (C^(1 + e) for C in [0, 1])
//
// The blur is the SDK's shared exact Gaussian; reference/edge_darkening.h is the reference.
#include <aquarelle/plugin.hpp>
#include <aquarelle/sdk/gaussian_blur.hpp>
#include <aquarelle/sdk/gl_raii.hpp>

#include <algorithm>
#include <cmath>
#include <vector>

#include "edge_darkening_shaders.h"

namespace {

enum Input : uint32_t { kImage, kSource, kControl };
constexpr aq_port_desc kInputs[] = {
    aq::image_port("image", "colour to darken (e.g. after bleeding)"),
    aq::optional_image_port("source",
                            "image whose blur difference finds the edges (the seed's colour "
                            "before bleeding); unconnected: the image itself"),
    aq::optional_image_port("control",
                            "control map: g edge-darkening amount, b grazing angle; "
                            "unconnected: k = strength everywhere")};
constexpr aq_port_desc kOutputs[] = {aq::image_port("image", "colour with darkened edges")};
enum Param : uint32_t { kSigma, kStrength, kGrazing, kMaxExponent, kResolution };
constexpr aq_param_desc kParams[] = {
    aq::float_param("sigma", 3.0, 0.0, 64.0,
                    "Gaussian sigma in output pixels (the seed's 3); 0 passes the image through"),
    aq::float_param("strength", 4.0, 0.0, 100.0,
                    "k: exponent gain per unit of blur difference; 0 passes the image through"),
    aq::float_param("grazing", 1.0, 0.0, 10.0,
                    "how much the grazing angle (control map blue) adds to k at silhouettes"),
    aq::float_param("max_exponent", 1.0, 0.0, 100.0,
                    "the darkening exponent saturates smoothly at this (1: at most C^2, no "
                    "black blots); 0: unbounded (C^(1 + k d))"),
    aq::int_param("resolution", 2, 1, 2,
                  "2: the blur runs on 2x2-pixel cells (sigma >= 1.5 px) and is read back "
                  "bilinearly; 1: every pixel, exact")};

// The rounding of a blurred constant image stays under this (relative to max(1, |source|)).
constexpr double kDeadZone = 1e-5;

// Bilinear reading back of a grid of spacing 2 widens a Gaussian by about this variance (px²),
// and the 2×2 average by 0.25: the cells' blur is narrower by both, so the sum is σ².
constexpr double kCellVariance = 0.25 + 4.0 / 6.0;

class EdgeDarkening {
 public:
  int process(aq::Context& ctx) {
    const aq_image in = ctx.input_image(kImage);
    const double sigma = ctx.param_float(kSigma) * ctx.render_scale();
    if (!(sigma > 0.0) || !(ctx.param_float(kStrength) > 0.0)) {
      return ctx.pass_through(0, kImage) ? AQ_OK : AQ_ERROR;
    }
    const aq_image source = ctx.connected(kSource) ? ctx.input_image(kSource) : in;
    aq_image blurred, out;
    if (!ctx.output_like(0, in, &out) || !blur_source(ctx, source, sigma, &blurred)) {
      kept_valid_ = false;
      return AQ_ERROR;
    }
    const GLuint program = ctx.program(shaders::edge_darkening_frag);
    if (program == 0) return AQ_ERROR;
    glUseProgram(program);
    aq::bind_texture(program, "u_image", 0, in);
    aq::bind_texture(program, "u_source", 1, source);
    aq::bind_texture(program, "u_blurred", 2, blurred);
    aq::bind_texture(program, "u_control", 3,
                     ctx.connected(kControl) ? ctx.input_image(kControl) : in);
    aq::set_int(program, "u_has_control", ctx.connected(kControl) ? 1 : 0);
    aq::set_float(program, "u_strength", ctx.param_float(kStrength));
    aq::set_float(program, "u_grazing", ctx.param_float(kGrazing));
    aq::set_float(program, "u_dead_zone", kDeadZone);
    aq::set_float(program, "u_max_exponent", ctx.param_float(kMaxExponent));
    aq::Region damage = damaged(ctx, source, out, sigma);
    if (!ctx.set_draw_region(damage)) damage = aq::Region::everything();
    const bool drawn = ctx.draw(out);
    ctx.set_draw_region(aq::Region::everything());
    aq::unbind_textures(4);
    return drawn && ctx.set_output_damage(0, damage) ? AQ_OK : AQ_ERROR;
  }

 private:
  // blur(source) at the source's size, or on 2×2 cells when asked and σ is wide enough.
  bool blur_source(aq::Context& ctx, const aq_image& source, double sigma, aq_image* blurred) {
    const bool cells =
        ctx.param_int(kResolution) >= 2 && sigma >= 1.5 && source.width >= 4 && source.height >= 4;
    if (!cells) {
      kept_valid_ = false;
      return ctx.scratch(source.width, source.height, AQ_FORMAT_RGBA32F, blurred) &&
             aq::gaussian::blur(ctx, source, *blurred, sigma, /*linear_taps=*/false);
    }
    const int w = (source.width + 1) / 2, h = (source.height + 1) / 2;
    bool kept = false;
    const GLuint name = kept_blurred_.get(ctx.raw()->gl_generation, w, h, GL_RGBA32F, &kept);
    if (!kept) {  // sampled as the pool's textures are: bilinear, clamped at the edges
      glTextureParameteri(name, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
      glTextureParameteri(name, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
      glTextureParameteri(name, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
      glTextureParameteri(name, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    }
    *blurred = aq_image{name, w, h, AQ_FORMAT_RGBA32F};
    aq_image averaged, horizontal;
    if (!ctx.scratch(w, h, AQ_FORMAT_RGBA32F, &averaged) ||
        !ctx.scratch(w, h, AQ_FORMAT_RGBA32F, &horizontal)) {
      return false;
    }
    const GLuint down = ctx.program(shaders::edge_darkening_down_frag);
    if (down == 0) return false;
    const double cell_sigma = std::sqrt(std::max(sigma * sigma - kCellVariance, 0.25)) / 2.0;
    // Damage tracking on the cells: the blurred cells are the node's own texture, kept between
    // calls; only the cells within the kernel's radius of a changed cell are blurred again (the
    // rows pass over the rows the columns pass reads, the averages under those).
    const aq::gaussian::Pass along_x = aq::gaussian::gaussian_pass(cell_sigma, w);
    const aq::gaussian::Pass along_y = aq::gaussian::gaussian_pass(cell_sigma, h);
    const int radius = std::max(along_x.radius, along_y.radius) + 1;
    const bool tails = along_x.tail > 0.0 || along_y.tail > 0.0;  // every cell reads the edge
    aq::Region changed = aq::Region::everything();
    if (kept && kept_valid_ && !tails) {
      changed = cells_of(ctx.input_damage(ctx.connected(kSource) ? kSource : kImage), w, h)
                    .dilated(1, 1, w, h);
    }
    const aq::Region blurred_region = changed.dilated(radius, radius, w, h).for_drawing();
    const aq::Region rows_region = blurred_region.dilated(0, radius, w, h).for_drawing();
    const aq::Region averaged_region = rows_region.dilated(radius, 0, w, h).for_drawing();
    kept_valid_ = false;
    glUseProgram(down);
    aq::bind_texture(down, "u_source", 0, source);
    ctx.set_draw_region(averaged_region);
    if (!ctx.draw(averaged)) return false;
    ctx.set_draw_region(rows_region);
    if (!aq::gaussian::blur_pass(ctx, averaged, horizontal, cell_sigma, 0, false)) return false;
    ctx.set_draw_region(blurred_region);
    if (!aq::gaussian::blur_pass(ctx, horizontal, *blurred, cell_sigma, 1, false)) return false;
    ctx.set_draw_region(aq::Region::everything());
    kept_valid_ = true;
    return true;
  }

  // The 2×2 cells holding the pixels of `pixels`.
  static aq::Region cells_of(const aq::Region& pixels, int w, int h) {
    if (pixels.all()) return pixels;
    std::vector<aq::PixelRect> rects;
    for (const aq::PixelRect& r : pixels.rects()) {
      rects.push_back(aq::PixelRect{r.x0 / 2, r.y0 / 2, std::min((r.x1 + 1) / 2, w),
                                    std::min((r.y1 + 1) / 2, h)});
    }
    aq::Region cells;
    cells.add(rects);
    return cells;
  }

  aq::gl::KeptTexture kept_blurred_;
  bool kept_valid_ = false;  // kept_blurred_ holds the blur of the last call's source

  // Damage tracking: the full-size pass is limited to the pixels whose own image texel changed,
  // whose blur can reach a changed source texel (4σ, plus the cells' averaging and bilinear reading
  // back), or whose control tent (one texel around) changed.
  static aq::Region damaged(const aq::Context& ctx, const aq_image& source, const aq_image& out,
                            double sigma) {
    if (!ctx.output_kept(0)) return aq::Region::everything();
    const int reach = static_cast<int>(std::ceil(aq::gaussian::kTruncationSigmas * sigma)) + 6;
    // Taps past a small image's edge read the edge texel from every pixel.
    if (2 * reach >= std::min(source.width, source.height)) return aq::Region::everything();
    if (source.width != out.width || source.height != out.height) return aq::Region::everything();
    aq::Region damage = ctx.input_damage(kImage);
    if (ctx.connected(kSource)) {
      damage.add(ctx.input_damage(kSource).dilated(reach, reach, out.width, out.height));
    } else {
      damage.add(damage.dilated(reach, reach, out.width, out.height));
    }
    if (ctx.connected(kControl)) {
      const aq_image control = ctx.input_image(kControl);
      if (control.width != out.width || control.height != out.height)
        return aq::Region::everything();
      damage.add(ctx.input_damage(kControl).dilated(1, 1, out.width, out.height));
    }
    return damage.for_drawing();
  }
};

}  // namespace

AQ_NODE(kEdgeDarkeningNode, EdgeDarkening, "edge_darkening", "Watercolor",
        "MNPR edge darkening: d = max_rgb |blur(C) - C| (sigma 3), output C^(1 + k d) with k from "
        "the control map, stronger at grazing angles.",
        0, kInputs, kOutputs, kParams);
AQ_PLUGIN("edge_darkening", "1.0", &kEdgeDarkeningNode)
