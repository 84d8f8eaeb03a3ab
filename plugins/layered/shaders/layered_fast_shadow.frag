// Soft shadows of the `fast` method (README "Fast method"): layered_shadow.glsl's r and g
// averaged over each low-resolution texel's D x D pixels; the shared Gaussian blurs them there
// and the composite divides the bilinearly enlarged sums, as the exact method does at full size.
// At D = 4 the average is taken over four of the sixteen pixels on a rotated grid, one in each
// row and each column, centred on the texel's centre (a quarter of the shadow-map tests, which
// were three quarters of this pass; a straight edge or a one-pixel line through the texel covers
// as many samples as it does pixels; error against the sixteen in README "Fast method").
layout(location = 0) out vec4 o_shadow;

void main() {
  ivec2 size = textureSize(u_id, 0);
  ivec2 base = AQ_DIVISOR * ivec2(gl_FragCoord.xy);
  vec2 sum = vec2(0.0);
#if AQ_DIVISOR == 4
  const ivec2 kRotatedGrid[4] = ivec2[](ivec2(0, 1), ivec2(2, 0), ivec2(1, 3), ivec2(3, 2));
  for (int k = 0; k < 4; ++k) sum += layered_shadow_at(min(base + kRotatedGrid[k], size - 1));
  o_shadow = vec4(sum / 4.0, 0.0, 0.0);
#else
  for (int j = 0; j < AQ_DIVISOR; ++j) {
    for (int i = 0; i < AQ_DIVISOR; ++i) {
      sum += layered_shadow_at(min(base + ivec2(i, j), size - 1));
    }
  }
  o_shadow = vec4(sum / float(AQ_DIVISOR * AQ_DIVISOR), 0.0, 0.0);
#endif
}
