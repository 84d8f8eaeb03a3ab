// Shared exact separable Gaussian: the body of one 1D pass, `#include "aquarelle/gaussian.glsl"`.
// The C++ side is nodes/include/aquarelle/sdk/gaussian_blur.hpp (aq::gaussian::blur), which
// computes the taps on the CPU in double, sets these uniforms and draws; most plugins never
// include this file themselves. A plugin that wants the pass inside its own shader includes it
// and calls aq_gaussian_pass(gl_FragCoord.xy) with the uniforms set by
// aq::gaussian::set_pass_uniforms.
//
// Table pass (default): u_gaussian_taps[i] = (offset in pixels, weight), read at ±offset;
// u_gaussian_taps[0] is the centre. Weights are the sampled Gaussian exp(-i²/2σ²) normalised
// over the truncated kernel (>= 4σ); with linear taps two neighbours are merged into one
// bilinear read; taps beyond the image are lumped into one per side. The sampler's
// clamp-to-edge gives the border rule. A table instead of exp() per tap: llvmpipe runs it about
// twice as fast.
//
// Wide pass (#define AQ_GAUSSIAN_WIDE 1 before the include): for kernels with more taps than
// the table holds (σ above ~120 px): the same maths, weights evaluated in the shader.
uniform sampler2D u_gaussian_image;
uniform vec2 u_gaussian_size;  // image size in pixels (input = output)
uniform vec2 u_gaussian_axis;  // (1, 0) or (0, 1)

// Positions in pixels first, divided once: a centre tap lands on the texel centre to the last
// bit (multiplying by 1/size instead mixes in up to 5e-6 of the neighbour).
vec4 aq_gaussian_tap(vec2 frag, float offset) {
  return texture(u_gaussian_image, (frag + offset * u_gaussian_axis) / u_gaussian_size);
}

#if !defined(AQ_GAUSSIAN_WIDE) || AQ_GAUSSIAN_WIDE == 0
uniform int u_gaussian_tap_count;
uniform vec2 u_gaussian_taps[256];  // gaussian_blur.hpp: kMaxTableTaps

vec4 aq_gaussian_pass(vec2 frag) {
  vec4 sum = u_gaussian_taps[0].y * aq_gaussian_tap(frag, 0.0);
  for (int i = 1; i < u_gaussian_tap_count; ++i) {
    sum += u_gaussian_taps[i].y *
           (aq_gaussian_tap(frag, u_gaussian_taps[i].x) + aq_gaussian_tap(frag, -u_gaussian_taps[i].x));
  }
  return sum;
}
#else
uniform int u_gaussian_radius;
uniform float u_gaussian_inv_two_sigma2;
uniform float u_gaussian_norm;
uniform float u_gaussian_tail;
uniform float u_gaussian_tail_offset;
uniform bool u_gaussian_linear_taps;

float aq_gaussian_weight(int i) {
  float x = float(i);
  return exp(-x * x * u_gaussian_inv_two_sigma2) * u_gaussian_norm;
}

vec4 aq_gaussian_pass(vec2 frag) {
  vec4 sum = u_gaussian_norm * aq_gaussian_tap(frag, 0.0);
  if (u_gaussian_linear_taps) {
    for (int i = 1; i <= u_gaussian_radius; i += 2) {
      float wa = aq_gaussian_weight(i);
      float wb = i + 1 <= u_gaussian_radius ? aq_gaussian_weight(i + 1) : 0.0;
      float w = wa + wb;
      if (w <= 0.0) break;  // the rest underflows too
      float offset = float(i) + wb / w;
      sum += w * (aq_gaussian_tap(frag, offset) + aq_gaussian_tap(frag, -offset));
    }
  } else {
    for (int i = 1; i <= u_gaussian_radius; ++i) {
      sum += aq_gaussian_weight(i) * (aq_gaussian_tap(frag, float(i)) + aq_gaussian_tap(frag, -float(i)));
    }
  }
  if (u_gaussian_tail > 0.0) {
    sum += u_gaussian_tail * (aq_gaussian_tap(frag, u_gaussian_tail_offset) +
                              aq_gaussian_tap(frag, -u_gaussian_tail_offset));
  }
  return sum;
}
#endif
