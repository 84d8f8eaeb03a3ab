// blur: the underwater blur of the seed paper (Paré-Vogt & Chaid §5.1, §7.2) whose strength
// grows with depth³ and with the distance from the viewport centre.
//
//   strength s(p) = clamp(depth_weight·min(z/distance_scale, 1)³ + radial_weight·r², 0, 1)
//   σ(p)          = sigma · s(p)
//
// `gaussian` (default): exact Gaussians. A uniform σ is two separable passes (horizontal into a
// scratch texture, then vertical). A varying σ with σmax <= 2 working pixels (the underwater
// graph at preview and final quality) is one pass: each pixel gathers the Gaussian of its own
// σ, truncated at 2·ceil(σmax) taps per side, read as bilinear pairs ((R+1)² fetches; at draft
// and preview quality and σmax <= 1, the 5-fetch `pinwheel` subset of the 5×5 taps). A wider
// varying σ renders a small stack of exact blurs at σmax, σmax/2, σmax/4 ... and mixes the two
// levels around each pixel's σ so that the mixed kernel has exactly the variance σ²
// (levels_per_octave = 2 or 3 puts levels closer):
//
//   image ─► H(σ1) ─► V(σ1) ─► level 1 ─┐
//         ─► H(σ2) ─► V(σ2) ─► level 2 ─┼─► composite(depth) ─► image
//         ─► ...                ...    ─┘
//
// Shaders that depend on the stack size or on the depth input are compiled per variant
// (#define), as llvmpipe runs every side of a branch on a uniform.
//
// `reduced_resolution` runs Gaussians above 4 px on a pyramid of 2×2 means and back up.
//
// `strided`: the seed's 5×5 kernel read with strides 0.3σ and σ, kept to show its artefacts.
#include <aquarelle/plugin.hpp>
#include <aquarelle/sdk/blocks.hpp>
#include <aquarelle/sdk/gaussian_blur.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "blur_shaders.h"

namespace {

constexpr aq_port_desc kInputs[] = {
    // AQ_PORT_HDR8: the separable direct kernel (final quality) decodes per tap; the other
    // methods decode the image once first.
    aq::image_port("image", "colour to blur", AQ_PORT_HDR8 | AQ_PORT_BLOCKS),
    aq::optional_image_port("depth",
                            "linear view depth (R32F); without it the depth term is 1 (far)")};
constexpr aq_port_desc kOutputs[] = {aq::image_port("image", "blurred colour")};
enum Param {
  kMethod,
  kSigma,
  kDistanceScale,
  kDepthWeight,
  kRadialWeight,
  kLinearTaps,
  kLevelsPerOctave,
  kReducedResolution,
  kDirectKernel
};
enum Method { kGaussian = 0, kStrided = 1 };
enum DirectKernel { kDirectAuto = 0, kDirectFull = 1, kDirectPinwheel = 2, kDirectSeparable = 3 };
constexpr aq_param_desc kParams[] = {
    aq::enum_param("method", "gaussian|strided", kGaussian,
                   "gaussian: exact separable Gaussian (default); strided: the seed's 5x5 kernel "
                   "with strides 0.3*sigma and sigma, which aliases (kept for comparison)"),
    aq::float_param("sigma", 4.0, 0.0, 256.0, "Gaussian sigma in pixels at full strength", 0.0,
                    "log"),
    aq::float_param("distance_scale", 20.0, 0.001, 1.0e6,
                    "view depth (scene units) at which the depth term reaches 1; it grows as "
                    "(depth / distance_scale)^3 before that. Choose it near the depth of the "
                    "farthest surface (a warning says when the whole frame is past it)",
                    0.0, "log"),
    aq::float_param("depth_weight", 1.0, 0.0, 1.0, "weight of the depth term in the strength"),
    aq::float_param("radial_weight", 0.35, 0.0, 1.0,
                    "weight of the squared distance from the centre (1 at the corners)"),
    aq::bool_param("linear_taps", true,
                   "read two Gaussian taps with one bilinear fetch (half the reads; error "
                   "measured in the tests)"),
    aq::int_param("levels_per_octave", 1, 1, 3,
                  "blurs per doubling of sigma in the stack used when sigma varies per pixel: "
                  "more is closer to the ideal per-pixel Gaussian and slower"),
    aq::bool_param("reduced_resolution", false,
                   "blur sigmas above 4 px (uniform, or the stack's levels) on a pyramid reduced "
                   "2^k times, sigma/2^k >= 2 px: much faster, error measured in the tests"),
    aq::enum_param("direct_kernel", "auto|full|pinwheel|separable", kDirectAuto,
                   "kernel for a varying sigma up to 2 working px: full = the truncated "
                   "Gaussian in one pass (9 reads up to 1 px, 25 up to 2 px); pinwheel = 17 of "
                   "the 5x5 taps (5 reads, up to 1 px, less accurate); separable = rows then "
                   "columns, each pixel with its own sigma (2 passes of 3 or 5 reads; differs "
                   "from full where sigma changes within the radius); auto = pinwheel at draft "
                   "and preview, full at final up to 1 px, separable above 1 px")};

constexpr int kMaxLevels = 12;          // blurred levels in the stack besides the input (shader)
constexpr double kSmallestLevel = 0.5;  // below this a Gaussian is nearly the identity
// Largest σmax (working pixels) blurred in one direct pass; its radius is 2·ceil(σmax), so at
// most 25 fetches, fewer than the stack's passes read at this size (README, cost).
constexpr double kDirectMaxSigma = 2.0;

// With `reduced_resolution`, Gaussians wider than this (working pixels) run on a pyramid.
constexpr double kPyramidMinSigma = 4.0;

// Pyramid levels for a Gaussian of σ: 2^k reductions leaving σ/2^k in [2, 4) reduced pixels.
int pyramid_levels(double sigma) {
  if (!(sigma > kPyramidMinSigma)) return 0;
  return static_cast<int>(std::floor(std::log2(sigma / 2.0)));
}

// The truncation radius of the direct pass for a given σmax: an even number >= 2σmax.
int direct_radius(double max_sigma) {
  return 2 * std::max(1, static_cast<int>(std::ceil(max_sigma - 1e-9)));
}

// `defines`, then the shared strength function, then a shader that calls it. The host caches
// programs by their text, so each variant compiles once.
aq_shader_source with_strength(const aq_shader_source& main, const std::string& defines,
                               std::string& storage) {
  storage = defines + shaders::blur_strength_glsl.text + "\n#line 1\n" + main.text;
  return aq_shader_source{main.name, storage.c_str(), nullptr};
}

std::string define(const char* name, int value) {
  return "#define " + std::string(name) + " " + std::to_string(value) + "\n";
}

// AQ_HAS_DEPTH for blur_strength.glsl: 0 none, 1 the image's size (texelFetch), 2 sampled.
std::string depth_define(const aq::Context& ctx, const aq_image& in) {
  if (!ctx.connected(1)) return define("AQ_HAS_DEPTH", 0);
  const aq_image depth = ctx.input_image(1);
  return define("AQ_HAS_DEPTH", depth.width == in.width && depth.height == in.height ? 1 : 2);
}

struct Blur {
  std::string source;  // the last composed shader text (the host compiles it at once)
  // The output pixels that may change (damage tracking; direct method only, else all), and
  // what is drawn for them.
  aq::Region damage_ = aq::Region::everything();
  aq::Region drawn_ = aq::Region::everything();

  int process(aq::Context& ctx) {
    aq_image in = ctx.input_image(0);
    const double sigma = ctx.param_float(kSigma) * ctx.render_scale();  // output pixels
    const double depth_weight = ctx.param_float(kDepthWeight);
    const double radial_weight = ctx.param_float(kRadialWeight);
    const bool has_depth = ctx.connected(1);
    // Without depth the strength is clamp(depth_weight + radial_weight·r²): uniform when the
    // radial term adds nothing.
    const bool uniform = !has_depth && (radial_weight <= 0.0 || depth_weight >= 1.0);
    const double max_strength = std::min(1.0, depth_weight + radial_weight);
    const double max_sigma = sigma * (uniform ? std::min(1.0, depth_weight) : max_strength);
    if (!(max_sigma > 0.0)) return unblurred(ctx, in) ? AQ_OK : AQ_ERROR;

    if (has_depth && depth_weight > 0.0) check_distance_scale(ctx);

    aq_image out;
    if (!ctx.output_like(0, in, &out)) return AQ_ERROR;
    const bool direct =
        ctx.param_enum(kMethod) != kStrided && !uniform && max_sigma <= kDirectMaxSigma;
    damage_ =
        direct ? direct_damage(ctx, in, out, direct_radius(max_sigma)) : aq::Region::everything();
    drawn_ = damage_.for_drawing();
    if (!ctx.set_draw_region(drawn_)) damage_ = drawn_ = aq::Region::everything();  // old host
    const bool encoded = in.format == AQ_FORMAT_RGBA8_HDR || aq::in_blocks(in);
    if (encoded && !reads_encoded(ctx, uniform, max_sigma)) {
      aq_image decoded;
      ctx.set_draw_region(
          drawn_.dilated(direct_radius(max_sigma), direct_radius(max_sigma), in.width, in.height)
              .for_drawing());
      if (!decode(ctx, in, &decoded)) return AQ_ERROR;
      in = decoded;
    }
    ctx.set_draw_region(drawn_);
    bool ok = false;
    if (ctx.param_enum(kMethod) == kStrided) {
      ok = strided(ctx, in, out, sigma);
    } else if (uniform) {
      aq_image horizontal;
      ok = ctx.scratch(in.width, in.height, scratch_format(ctx), &horizontal) &&
           blur_into(ctx, in, horizontal, out, max_sigma);
    } else if (max_sigma <= kDirectMaxSigma) {
      ok = direct_gaussian(ctx, in, out, sigma, max_sigma);
    } else {
      ok = variable_gaussian(ctx, in, out, sigma, max_sigma);
    }
    aq::unbind_textures(16);
    return ok && ctx.set_output_damage(0, damage_) ? AQ_OK : AQ_ERROR;
  }

  // Once per value of distance_scale: when every surface in the frame is farther than it, the
  // depth term is 1 everywhere and the whole frame is blurred at full strength (a scene built
  // at another scale than distance_scale's default): a warning naming the frame's depths so
  // the parameter can be chosen (README, "Choosing distance_scale"). Depth 0 or not finite
  // (a background without environment) is skipped; the g-buffer's environment background
  // (the far plane) counts, as the blur treats it as far.
  double checked_scale_ = -1.0;
  void check_distance_scale(const aq::Context& ctx) {
    const double scale = ctx.param_float(kDistanceScale);
    if (scale == checked_scale_) return;
    checked_scale_ = scale;
    const aq_image depth = ctx.input_image(1);
    std::vector<float> z(static_cast<size_t>(depth.width) * depth.height);
    glGetTextureImage(depth.texture, 0, GL_RED, GL_FLOAT,
                      static_cast<GLsizei>(z.size() * sizeof(float)), z.data());
    double nearest = HUGE_VAL, farthest = 0.0;
    for (float d : z) {
      if (!(d > 0.0f) || !std::isfinite(d)) continue;
      nearest = std::min(nearest, double(d));
      farthest = std::max(farthest, double(d));
    }
    if (!(farthest > 0.0) || nearest < scale) return;
    char text[512];
    std::snprintf(text, sizeof(text),
                  "parameter 'distance_scale' (%g) is nearer than every pixel of the frame "
                  "(depths %.3g to %.3g scene units from the camera): the whole frame is "
                  "blurred at full strength; distance_scale is in the scene's units: set it to "
                  "about the depth that should be fully blurred, e.g. between %.3g and %.3g",
                  scale, nearest, farthest, nearest, farthest);
    ctx.warn(text);
  }

  // Damage tracking for the direct kernels (each output pixel reads the image and the depth
  // within `radius`, the radial term is fixed): with the output kept, the pixels within
  // `radius` of a changed image or depth pixel, and those the epilogue's inputs changed.
  static aq::Region direct_damage(const aq::Context& ctx, const aq_image& in, const aq_image& out,
                                  int radius) {
    if (!ctx.output_kept(0) || in.width != out.width || in.height != out.height)
      return aq::Region::everything();
    aq::Region changed = ctx.input_damage(0);
    if (ctx.connected(1)) {
      const aq_image depth = ctx.input_image(1);
      const aq::Region depth_changed = ctx.input_damage(1);
      const bool same_pixels = depth.width == in.width && depth.height == in.height;
      changed.add(same_pixels || depth_changed.empty() ? depth_changed : aq::Region::everything());
    }
    aq::Region damage = changed.dilated(radius, radius, out.width, out.height);
    damage.add(ctx.epilogue_damage());
    return damage;
  }

  // Intermediate textures are float in both precisions: RGBA16F ones were no faster on
  // llvmpipe and doubled the error in half precision (README).
  static uint32_t scratch_format(const aq::Context&) { return AQ_FORMAT_RGBA32F; }

  // Exact separable Gaussian of `in` into `out` (same size), through `horizontal`, a
  // texture of the same size: the SDK's shared Gaussian (aquarelle/sdk/gaussian_blur.hpp).
  static bool gaussian(aq::Context& ctx, const aq_image& in, const aq_image& horizontal,
                       const aq_image& out, double sigma) {
    return aq::gaussian::blur(ctx, in, horizontal, out, sigma, ctx.param_bool(kLinearTaps));
  }

  // A Gaussian of σ from `in` into `out` (same size): exact through the full-size scratch
  // `horizontal`, or, with `reduced_resolution` and σ above kPyramidMinSigma, down a pyramid of
  // 2×2 means k times (scale s = 2^k), an exact Gaussian of σ' there and bilinear back up. The
  // box steps add (s² − 1)/12 px² of variance per axis and the bilinear step (2s² + 1)/12 on
  // average, so σ'² = σ²/s² − 1/4 (README).
  bool blur_into(aq::Context& ctx, const aq_image& in, const aq_image& horizontal,
                 const aq_image& out, double sigma) {
    const int levels = ctx.param_bool(kReducedResolution) ? pyramid_levels(sigma) : 0;
    if (levels == 0) return gaussian(ctx, in, horizontal, out, sigma);
    const uint32_t format = scratch_format(ctx);
    aq_image level = in;
    for (int j = 0; j < levels; ++j) {
      aq_image half;
      if (!ctx.scratch((level.width + 1) / 2, (level.height + 1) / 2, format, &half)) return false;
      GLuint program = ctx.program(shaders::blur_downsample_frag);
      if (program == 0) return false;
      glUseProgram(program);
      aq::bind_texture(program, "u_image", 0, level);
      aq::set_vec2(program, "u_source_size", level.width, level.height);
      if (!ctx.draw(half)) return false;
      level = half;
    }
    const double scale = std::exp2(levels);
    aq_image reduced_horizontal, blurred;
    if (!ctx.scratch(level.width, level.height, format, &reduced_horizontal) ||
        !ctx.scratch(level.width, level.height, format, &blurred) ||
        !gaussian(ctx, level, reduced_horizontal, blurred,
                  std::sqrt(sigma * sigma / (scale * scale) - 0.25))) {
      return false;
    }
    GLuint program = ctx.program(shaders::blur_upsample_frag);
    if (program == 0) return false;
    glUseProgram(program);
    aq::bind_texture(program, "u_image", 0, blurred);
    aq::set_vec2(program, "u_reduced_extent", scale * blurred.width, scale * blurred.height);
    return ctx.draw(out);
  }

  // σ per pixel, σmax small: one pass, each pixel's own truncated Gaussian.
  bool direct_gaussian(aq::Context& ctx, const aq_image& in, const aq_image& out, double sigma,
                       double max_sigma) {
    const int radius = direct_radius(max_sigma);
    const int64_t kernel = ctx.param_enum(kDirectKernel);
    const bool pinwheel =
        radius == 2 && (kernel == kDirectPinwheel || (kernel == kDirectAuto && ctx.quality() < 2));
    // Above 1 px the one pass reads 25 texels; two passes of 5 cost less (README, cost).
    if (kernel == kDirectSeparable || (kernel == kDirectAuto && radius > 2)) {
      return separable_gaussian(ctx, in, out, sigma, radius);
    }
    const std::string defines =
        define("AQ_RADIUS", radius) + define("AQ_PINWHEEL", pinwheel) + depth_define(ctx, in);
    GLuint program = ctx.program(with_strength(shaders::blur_direct_frag, defines, source));
    if (program == 0) return false;
    glUseProgram(program);
    set_strength_uniforms(ctx, program, in);
    aq::bind_texture(program, "u_image", 0, in);
    aq::set_float(program, "u_sigma", sigma);
    return ctx.draw(out);
  }

  // Whether the method these parameters choose reads an encoded image itself (the separable
  // direct kernel); the others get it decoded first.
  static bool reads_encoded(const aq::Context& ctx, bool uniform, double max_sigma) {
    if (ctx.param_enum(kMethod) == kStrided || uniform || max_sigma > kDirectMaxSigma) return false;
    const int64_t kernel = ctx.param_enum(kDirectKernel);
    return kernel == kDirectSeparable || (kernel == kDirectAuto && direct_radius(max_sigma) > 2);
  }

  bool decode(aq::Context& ctx, const aq_image& in, aq_image* decoded) {
    return ctx.scratch(in.width, in.height, scratch_format(ctx), decoded) &&
           decode_into(ctx, in, *decoded);
  }

  // An encoded image (pixels or 2 x 2 blocks) decoded into `target`, of its size.
  bool decode_into(aq::Context& ctx, const aq_image& in, const aq_image& target) {
    source = std::string("#define AQ_BLOCKS ") + (aq::in_blocks(in) ? "1" : "0") + "\n" +
             shaders::blur_decode_frag.text;
    const GLuint program =
        ctx.program(aq_shader_source{shaders::blur_decode_frag.name, source.c_str(), nullptr});
    if (program == 0) return false;
    glUseProgram(program);
    if (aq::in_blocks(in)) {
      aq::bind_blocks(program, in, in);
    } else {
      aq::bind_texture(program, "u_image", 0, in);
    }
    return ctx.draw(target);
  }

  // σ = 0: the image itself, passed through; an image in blocks is drawn out as pixels, which
  // is what readers of the output take.
  bool unblurred(aq::Context& ctx, const aq_image& in) {
    if (!aq::in_blocks(in)) return ctx.pass_through(0, 0);
    aq_image out;
    return ctx.output_like(0, in, &out) && decode_into(ctx, in, out);
  }

  // σ per pixel, σmax small: rows then columns, each pixel with its own σ (a float scratch
  // between the passes, as the exact separable blur; when the input is encoded, encoded 2 x 2
  // blocks, which is what makes both passes' taps cheap: blur_direct_separable.frag;
  // AQUARELLE_BLUR_BLOCKS=0 keeps encoded pixels, the lever table).
  bool separable_gaussian(aq::Context& ctx, const aq_image& in, const aq_image& out, double sigma,
                          int radius) {
    const bool blocks_in = aq::in_blocks(in);
    const bool encoded = in.format == AQ_FORMAT_RGBA8_HDR || blocks_in;
    const char* blocks_lever = std::getenv("AQUARELLE_BLUR_BLOCKS");  // per call: tests flip it
    // An input in blocks is read as blocks whatever the lever says.
    const bool blocks =
        blocks_in || (encoded && (blocks_lever == nullptr || std::string(blocks_lever) != "0"));
    aq_image rows;
    const uint32_t rows_format = blocks    ? static_cast<uint32_t>(AQ_FORMAT_RGBA8_HDR_BLOCKS)
                                 : encoded ? in.format
                                           : scratch_format(ctx);
    if (!ctx.scratch(in.width, in.height, rows_format, &rows)) return false;
    for (int axis = 0; axis < 2; ++axis) {
      const aq_image& target = axis == 0 ? rows : out;
      const std::string defines = define("AQ_RADIUS", radius) + define("AQ_AXIS", axis) +
                                  depth_define(ctx, in) + define("AQ_DECODE_HDR8", encoded) +
                                  define("AQ_ENCODE_HDR8", target.format == AQ_FORMAT_RGBA8_HDR) +
                                  define("AQ_BLOCKS", blocks) + define("AQ_BLOCKS_IN", blocks_in);
      GLuint program =
          ctx.program(with_strength(shaders::blur_direct_separable_frag, defines, source));
      if (program == 0) return false;
      glUseProgram(program);
      set_strength_uniforms(ctx, program, in);
      if (axis == 1 && blocks) {
        aq::bind_blocks(program, rows, in);
      } else if (axis == 0 && blocks_in) {
        aq::bind_blocks(program, in, in);
      } else {
        aq::bind_texture(program, "u_image", 0, axis == 0 ? in : rows);
      }
      aq::set_float(program, "u_sigma", sigma);
      // The rows pass covers the rows the columns pass reads around the damaged pixels, in
      // whole blocks when it writes them.
      const aq::Region rows_drawn = drawn_.dilated(0, radius, out.width, out.height);
      ctx.set_draw_region(axis == 1 ? drawn_
                          : blocks  ? aq::blocks_of(rows_drawn).for_drawing()
                                    : rows_drawn.for_drawing());
      if (!ctx.draw(axis == 0 ? rows : out)) return false;
    }
    return true;
  }

  // σ per pixel: a stack of exact blurs mixed per pixel by the composite shader.
  bool variable_gaussian(aq::Context& ctx, const aq_image& in, const aq_image& out, double sigma,
                         double max_sigma) {
    const double ratio = std::exp2(1.0 / static_cast<double>(ctx.param_int(kLevelsPerOctave)));
    std::vector<double> level_sigmas{max_sigma};
    while (static_cast<int>(level_sigmas.size()) < kMaxLevels &&
           level_sigmas.back() / ratio >= kSmallestLevel) {
      level_sigmas.push_back(level_sigmas.back() / ratio);
    }
    level_sigmas.push_back(0.0);  // level 0: the input itself
    std::reverse(level_sigmas.begin(), level_sigmas.end());

    const uint32_t format = scratch_format(ctx);
    aq_image horizontal;
    if (!ctx.scratch(in.width, in.height, format, &horizontal)) return false;
    std::vector<aq_image> levels{in};
    for (size_t k = 1; k < level_sigmas.size(); ++k) {
      aq_image level;
      if (!ctx.scratch(in.width, in.height, format, &level)) return false;
      if (!blur_into(ctx, in, horizontal, level, level_sigmas[k])) return false;
      levels.push_back(level);
    }

    const int count = static_cast<int>(levels.size());
    const std::string defines = define("AQ_LEVEL_COUNT", count) + depth_define(ctx, in);
    GLuint program = ctx.program(with_strength(shaders::blur_composite_frag, defines, source));
    if (program == 0) return false;
    glUseProgram(program);
    set_strength_uniforms(ctx, program, in);
    // σ² of each level and the reciprocal gaps between neighbours, in double, rounded once.
    std::vector<float> sigma2(count), rise(count, 0.0f), fall(count, 0.0f);
    for (int k = 0; k < count; ++k) {
      const std::string name = "u_levels[" + std::to_string(k) + "]";
      aq::bind_texture(program, name.c_str(), static_cast<GLuint>(k), levels[k]);
      const double s2 = level_sigmas[k] * level_sigmas[k];
      sigma2[k] = static_cast<float>(s2);
      if (k > 0)
        rise[k] = static_cast<float>(1.0 / (s2 - level_sigmas[k - 1] * level_sigmas[k - 1]));
      if (k + 1 < count) {
        fall[k] = static_cast<float>(1.0 / (level_sigmas[k + 1] * level_sigmas[k + 1] - s2));
      }
    }
    glUniform1fv(glGetUniformLocation(program, "u_level_sigma2"), count, sigma2.data());
    glUniform1fv(glGetUniformLocation(program, "u_rise"), count, rise.data());
    glUniform1fv(glGetUniformLocation(program, "u_fall"), count, fall.data());
    aq::set_float(program, "u_sigma", sigma);
    return ctx.draw(out);
  }

  bool strided(aq::Context& ctx, const aq_image& in, const aq_image& out, double sigma) {
    GLuint program =
        ctx.program(with_strength(shaders::blur_strided_frag, depth_define(ctx, in), source));
    if (program == 0) return false;
    glUseProgram(program);
    set_strength_uniforms(ctx, program, in);
    aq::bind_texture(program, "u_image", 0, in);
    aq::set_float(program, "u_sigma", sigma);
    return ctx.draw(out);
  }

  // Uniforms of blur_strength.glsl; the depth texture goes on unit 15, after the levels.
  static void set_strength_uniforms(aq::Context& ctx, GLuint program, const aq_image& in) {
    const bool has_depth = ctx.connected(1);
    if (has_depth) aq::bind_texture(program, "u_depth", 15, ctx.input_image(1));
    aq::set_float(program, "u_distance_scale", ctx.param_float(kDistanceScale));
    aq::set_float(program, "u_depth_weight", ctx.param_float(kDepthWeight));
    aq::set_float(program, "u_radial_weight", ctx.param_float(kRadialWeight));
    aq::set_vec2(program, "u_size", in.width, in.height);
  }
};

}  // namespace

AQ_NODE(kBlurNode, Blur, "blur", "Filter",
        "Underwater blur growing with depth^3 and distance from the centre: exact separable "
        "Gaussian (default) or the seed's strided 5x5 kernel.",
        AQ_NODE_EPILOGUE, kInputs, kOutputs, kParams);
AQ_PLUGIN("blur", "1.0", &kBlurNode)
