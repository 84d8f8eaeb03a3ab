// The shared exact Gaussian blur of the plugin SDK: any plugin blurs an aq_image by σ through
// the host services with one call, and never carries its own copy of a blur.
//
//   #include <aquarelle/sdk/gaussian_blur.hpp>
//   aq_image out;                                   // same size as `in`, e.g. an output
//   if (!aq::gaussian::blur(ctx, in, out, sigma)) return AQ_ERROR;   // host->fail was called
//
//   in ─► horizontal pass ─► scratch (RGBA32F, from the pool) ─► vertical pass ─► out
//
// σ is in working pixels (multiply a parameter given in output pixels by ctx.render_scale()).
// σ <= 0 (or NaN) copies `in` into `out` through the same pass with the centre tap only.
// Borders clamp to the edge texel (the sampler's rule); σ larger than the image is exact: taps
// beyond the image read the edge texel, so they are lumped into one "tail" tap per side. All
// four channels are blurred alike. The result equals the clamp-to-edge Gaussian of
// reference/blur.h (gaussian_blur) truncated at 4σ: per pass the truncation error is
// below 6.4e-5 of the range; with `linear_taps` (two taps per bilinear fetch, half the reads)
// the error stays at the rounding of the sampler's weights (~1e-4, measured in blur_test).
//
// The GLSL lives in nodes/shaders/gaussian.glsl (one 1D pass); this header computes its taps in
// double (gaussian_pass, gaussian_taps), sets its uniforms and draws it. Plugins built outside
// the tree get it from the installed SDK like plugin.hpp.
//
// Leaves a program and textures bound: call aq::unbind_textures before returning from process.
#pragma once

#include <aquarelle/plugin.hpp>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

namespace aq::gaussian {

// Taps reach at least this many sigmas (truncation error per pass below 6.4e-5 of the range).
constexpr double kTruncationSigmas = 4.0;

// The numbers one 1D pass needs, in double so the shader only multiplies.
struct Pass {
  double sigma = 0.0;
  int radius = 0;               // taps -radius..radius are read one by one (or in pairs)
  double inv_two_sigma2 = 0.0;  // weight(i) = exp(-i² · inv_two_sigma2) · norm
  double norm = 1.0;            // 1 / sum of the weights over the truncated kernel
  double tail = 0.0;            // normalised weight of the taps beyond `radius` on one side
  int tail_offset = 0;          // where the tail tap reads: always past the image edge
};

// `length` is the image size along the pass direction.
inline Pass gaussian_pass(double sigma, int length) {
  Pass pass;
  pass.sigma = sigma;
  if (!(sigma > 0.0)) return pass;  // identity: centre tap only
  const int truncation = static_cast<int>(std::ceil(kTruncationSigmas * sigma));
  pass.inv_two_sigma2 = 1.0 / (2.0 * sigma * sigma);
  double sum = 1.0;
  for (int i = 1; i <= truncation; ++i) sum += 2.0 * std::exp(-i * (i * pass.inv_two_sigma2));
  pass.norm = 1.0 / sum;
  // Taps at |i| >= length read the edge texel from every pixel of the image.
  pass.radius = std::min(truncation, std::max(length - 1, 0));
  for (int i = pass.radius + 1; i <= truncation; ++i) {
    pass.tail += std::exp(-i * (i * pass.inv_two_sigma2)) * pass.norm;
  }
  pass.tail_offset = std::max(length, 1);
  return pass;
}

// Entries of gaussian.glsl's u_gaussian_taps table; longer kernels use its wide variant.
constexpr size_t kMaxTableTaps = 256;

struct Tap {
  float offset;  // pixels; read at ±offset (the centre tap once)
  float weight;  // per side
};

// The pass as a table: the centre, then single taps or bilinear pairs, then the tail. Weights
// are evaluated in double and rounded once.
inline std::vector<Tap> gaussian_taps(const Pass& pass, bool linear_taps) {
  auto weight = [&](int i) { return std::exp(-i * (i * pass.inv_two_sigma2)) * pass.norm; };
  std::vector<Tap> taps{{0.0f, static_cast<float>(pass.norm)}};
  if (linear_taps) {
    for (int i = 1; i <= pass.radius; i += 2) {
      const double wa = weight(i);
      const double wb = i + 1 <= pass.radius ? weight(i + 1) : 0.0;
      if (wa + wb <= 0.0) break;  // the rest underflows too
      taps.push_back({static_cast<float>(i + wb / (wa + wb)), static_cast<float>(wa + wb)});
    }
  } else {
    for (int i = 1; i <= pass.radius; ++i) {
      taps.push_back({static_cast<float>(i), static_cast<float>(weight(i))});
    }
  }
  if (pass.tail > 0.0) {
    taps.push_back({static_cast<float>(pass.tail_offset), static_cast<float>(pass.tail)});
  }
  return taps;
}

// The fragment shaders of one pass: the table variant and the wide one.
inline const aq_shader_source& table_shader() {
  static const aq_shader_source source{
      "aquarelle/gaussian.glsl (table pass)",
      "#include \"aquarelle/gaussian.glsl\"\nlayout(location = 0) out vec4 o_color;\n"
      "void main() { o_color = aq_gaussian_pass(gl_FragCoord.xy); }\n",
      nullptr};
  return source;
}
inline const aq_shader_source& wide_shader() {
  static const aq_shader_source source{
      "aquarelle/gaussian.glsl (wide pass)",
      "#define AQ_GAUSSIAN_WIDE 1\n#include \"aquarelle/gaussian.glsl\"\n"
      "layout(location = 0) out vec4 o_color;\n"
      "void main() { o_color = aq_gaussian_pass(gl_FragCoord.xy); }\n",
      nullptr};
  return source;
}

// Sets gaussian.glsl's uniforms on the bound `program` for one pass of `pass` over an image of
// `size` along `axis` (0 horizontal, 1 vertical). `wide` selects the variant's uniforms.
inline void set_pass_uniforms(GLuint program, const Pass& pass, const std::vector<Tap>& taps,
                              bool wide, bool linear_taps, int axis, int width, int height) {
  aq::set_vec2(program, "u_gaussian_size", width, height);
  aq::set_vec2(program, "u_gaussian_axis", axis == 0 ? 1.0 : 0.0, axis == 1 ? 1.0 : 0.0);
  if (!wide) {
    aq::set_int(program, "u_gaussian_tap_count", static_cast<int>(taps.size()));
    static_assert(sizeof(Tap) == 2 * sizeof(float));
    glUniform2fv(glGetUniformLocation(program, "u_gaussian_taps"),
                 static_cast<GLsizei>(taps.size()), &taps[0].offset);
    return;
  }
  aq::set_int(program, "u_gaussian_linear_taps", linear_taps ? 1 : 0);
  aq::set_int(program, "u_gaussian_radius", pass.radius);
  aq::set_float(program, "u_gaussian_inv_two_sigma2", pass.inv_two_sigma2);
  aq::set_float(program, "u_gaussian_norm", pass.norm);
  aq::set_float(program, "u_gaussian_tail", pass.tail);
  aq::set_float(program, "u_gaussian_tail_offset", pass.tail_offset);
}

// One 1D pass of σ from `source` into `target` (same size) along `axis` (0 x, 1 y).
inline bool blur_pass(const aq::Context& ctx, const aq_image& source, const aq_image& target,
                      double sigma, int axis, bool linear_taps = true) {
  const Pass pass = gaussian_pass(sigma, axis == 0 ? source.width : source.height);
  const std::vector<Tap> taps = gaussian_taps(pass, linear_taps);
  const bool wide = taps.size() > kMaxTableTaps;
  const GLuint program = ctx.program(wide ? wide_shader() : table_shader());
  if (program == 0) return false;
  glUseProgram(program);
  aq::bind_texture(program, "u_gaussian_image", 0, source);
  set_pass_uniforms(program, pass, taps, wide, linear_taps, axis, source.width, source.height);
  return ctx.draw(target);
}

// The separable Gaussian of σ from `in` into `out` (same size) through `horizontal`, a texture
// of that size the caller owns (reuse one across several blurs).
inline bool blur(const aq::Context& ctx, const aq_image& in, const aq_image& horizontal,
                 const aq_image& out, double sigma, bool linear_taps = true) {
  return blur_pass(ctx, in, horizontal, sigma, 0, linear_taps) &&
         blur_pass(ctx, horizontal, out, sigma, 1, linear_taps);
}

// The same with the intermediate taken from the pool (RGBA32F: RGBA16F intermediates were no
// faster on llvmpipe and doubled the error in half precision, plugins/blur/README.md).
inline bool blur(const aq::Context& ctx, const aq_image& in, const aq_image& out, double sigma,
                 bool linear_taps = true) {
  aq_image horizontal;
  if (!ctx.scratch(in.width, in.height, AQ_FORMAT_RGBA32F, &horizontal)) return false;
  return blur(ctx, in, horizontal, out, sigma, linear_taps);
}

}  // namespace aq::gaussian
