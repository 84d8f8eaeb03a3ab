// Variable blur in one pass for a small σmax: at each pixel, the sampled Gaussian of that
// pixel's own σ, truncated at AQ_RADIUS taps per side (a compile-time constant, even) and
// normalised over the (2·AQ_RADIUS + 1)² taps, i.e. the ideal per-pixel Gaussian up to the
// truncation. Weights are per pixel, w(i) = exp(−i²/2σ²) = q^(i²), q = 2^(−log2(e)/2σ²), so
// no tables. Per axis the taps 2k−1 and 2k (k = 1..AQ_RADIUS/2) are read as one bilinear
// fetch at 2k−1 + w(2k)/(w(2k−1) + w(2k)); the kernel is separable, so the 2D sum is the
// outer product of the per-axis fetches: (AQ_RADIUS + 1)² reads in all (the centre one a
// texelFetch), exact in real arithmetic.
// With AQ_PINWHEEL (radius 2 only, the `direct_kernel` setting of draft and preview quality)
// the 5×5 support loses its 4 corners and 4 of its 8 other outer texels, (−2, 1), (1, 2),
// (2, −1), (−1, −2), so that what is left tiles into the centre texel and four 2×2 blocks
// turned by 90° about it: 5 reads instead of 9, each block exact as one bilinear fetch since
// the kernel is separable. The kernel keeps its 90° rotations but not its mirror symmetry.
// blur.cpp prepends AQ_RADIUS, AQ_PINWHEEL and AQ_HAS_DEPTH and the strength function.
layout(location = 0) out vec4 o_color;

uniform sampler2D u_image;
uniform float u_sigma;  // σ at strength 1, working pixels

float blur_strength(vec2 frag);

const int kPairs = AQ_RADIUS / 2;

#if AQ_PINWHEEL
void main() {
  vec2 frag = gl_FragCoord.xy;
  float sigma = u_sigma * blur_strength(frag);
  float log2_q = sigma > 0.0 ? -0.7213475204444817 / (sigma * sigma) : -1.0e30;
  float w1 = exp2(log2_q);
  float ratio = exp2(3.0 * log2_q);  // w(2) / w(1)
  // The block {1, 2} × {0, 1}: along x taps 1, 2, across taps 0, 1.
  float along = 1.0 + ratio / (1.0 + ratio);
  float across = w1 / (1.0 + w1);
  float block = w1 * (1.0 + ratio) * (1.0 + w1);
  vec2 inv_size = 1.0 / u_size;
  vec4 centre = texelFetch(u_image, ivec2(frag), 0);
  vec4 blocks = texture(u_image, (frag + vec2(along, across)) * inv_size) +
                texture(u_image, (frag + vec2(-across, along)) * inv_size) +
                texture(u_image, (frag + vec2(-along, -across)) * inv_size) +
                texture(u_image, (frag + vec2(across, -along)) * inv_size);
  o_color = w1 > 0.0 ? (centre + block * blocks) / (1.0 + 4.0 * block) : centre;
  o_color = aq_epilogue(o_color);  // the pointwise nodes after the blur, when the host fuses them
}
#else
void main() {
  vec2 frag = gl_FragCoord.xy;
  float sigma = u_sigma * blur_strength(frag);
  // log2 q; σ = 0 makes every weight but the centre's 0 (a select, not a branch: llvmpipe
  // would run both sides).
  float log2_q = sigma > 0.0 ? -0.7213475204444817 / (sigma * sigma) : -1.0e30;

  // Per-axis fetch offsets (pixels) and weights: index 0 the centre, k the pair (2k−1, 2k).
  float offset[kPairs + 1];
  float weight[kPairs + 1];
  offset[0] = 0.0;
  weight[0] = 1.0;
  float norm = 1.0;
  for (int k = 1; k <= kPairs; ++k) {
    float i = float(2 * k - 1);
    float ratio = exp2((2.0 * i + 1.0) * log2_q);  // w(2k) / w(2k−1): no 0/0 on underflow
    offset[k] = i + ratio / (1.0 + ratio);
    weight[k] = exp2(i * i * log2_q) * (1.0 + ratio);
    norm += 2.0 * weight[k];
  }

  // Texture coordinates by multiplication: a neighbour fetch may mix in ~5e-6 of the texel
  // next to where it should land, well below the truncation error.
  vec2 inv_size = 1.0 / u_size;
  vec4 centre = texelFetch(u_image, ivec2(frag), 0);
  vec4 sum = vec4(0.0);
  for (int b = -kPairs; b <= kPairs; ++b) {
    float dy = b < 0 ? -offset[-b] : offset[b];
    vec4 row = vec4(0.0);
    for (int a = -kPairs; a <= kPairs; ++a) {
      float dx = a < 0 ? -offset[-a] : offset[a];
      vec4 texel =
          a == 0 && b == 0 ? centre : texture(u_image, (frag + vec2(dx, dy)) * inv_size);
      row += weight[abs(a)] * texel;
    }
    sum += weight[abs(b)] * row;
  }
  // σ so small that every neighbour weight underflows: the input itself, exactly, so that a
  // non-finite neighbour (0 · ∞) cannot leak into a sharp pixel.
  float inv_norm = 1.0 / norm;
  o_color = weight[1] > 0.0 ? sum * (inv_norm * inv_norm) : centre;
  o_color = aq_epilogue(o_color);  // the pointwise nodes after the blur, when the host fuses them
}
#endif
