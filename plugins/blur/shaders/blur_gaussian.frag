// One 1D pass of the exact Gaussian blur along the pass direction, with the taps computed on
// the CPU (gaussian_pass.h): u_taps[i] = (offset in pixels, weight), read at ±offset;
// u_taps[0] is the centre. Weights are the sampled Gaussian exp(-i²/2σ²) normalised over the
// truncated kernel (>= 4σ); with linear taps two neighbours are merged into one bilinear read;
// taps beyond the image are lumped into one per side. The sampler's clamp-to-edge gives the
// border rule. A table instead of exp() per tap: llvmpipe runs this about twice as fast.
layout(location = 0) out vec4 o_color;

uniform sampler2D u_image;
uniform vec2 u_size;  // image size in pixels
uniform vec2 u_axis;  // (1, 0) or (0, 1)
uniform int u_tap_count;
uniform vec2 u_taps[256];   // gaussian_pass.h: kMaxTableTaps

// Positions in pixels first, divided once: a centre tap lands on the texel centre to the last
// bit (multiplying by 1/size instead mixes in up to 5e-6 of the neighbour).
vec4 tap(float offset) {
  return texture(u_image, (gl_FragCoord.xy + offset * u_axis) / u_size);
}

void main() {
  vec4 sum = u_taps[0].y * tap(0.0);
  for (int i = 1; i < u_tap_count; ++i) {
    sum += u_taps[i].y * (tap(u_taps[i].x) + tap(-u_taps[i].x));
  }
  o_color = sum;
}
