// Soft shadows of the `fast` method (README "Fast method"): layered_shadow.glsl's r and g
// averaged over each low-resolution texel's D x D pixels; the shared Gaussian blurs them there
// and the composite divides the bilinearly enlarged sums, as the exact method does at full size.
layout(location = 0) out vec4 o_shadow;

void main() {
  ivec2 size = textureSize(u_id, 0);
  ivec2 base = AQ_DIVISOR * ivec2(gl_FragCoord.xy);
  vec2 sum = vec2(0.0);
  for (int j = 0; j < AQ_DIVISOR; ++j) {
    for (int i = 0; i < AQ_DIVISOR; ++i) {
      sum += layered_shadow_at(min(base + ivec2(i, j), size - 1));
    }
  }
  o_shadow = vec4(sum / float(AQ_DIVISOR * AQ_DIVISOR), 0.0, 0.0);
}
