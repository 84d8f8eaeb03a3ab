// Soft shadows of the exact method (README "Soft shadows"): layered_shadow.glsl's r and g per
// pixel, blurred next by the shared Gaussian.
layout(location = 0) out vec4 o_shadow;

void main() {
  o_shadow = vec4(layered_shadow_at(ivec2(gl_FragCoord.xy)), 0.0, 0.0);
}
