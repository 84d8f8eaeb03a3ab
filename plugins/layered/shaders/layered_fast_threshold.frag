// The `fast` method's abstraction threshold per pixel (layered_common.glsl's noise-modulated
// threshold), drawn once and kept while the size and the threshold's parameters stay: the
// composite reads it instead of three octaves of gradient noise per pixel.
layout(location = 0) out vec4 o_threshold;

void main() {
  o_threshold = vec4(layered_threshold(gl_FragCoord.xy));
}
