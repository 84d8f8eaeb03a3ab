// The `fast` method's abstraction threshold per pixel (layered_common.glsl's noise-modulated
// threshold) and the paper's height there (0.5 where it is not finite in [0, 1] or there is no
// paper), drawn once and kept while the size, the threshold's parameters and the paper stay:
// the composite reads one texel instead of three octaves of gradient noise and the paper.
layout(location = 0) out vec4 o_threshold;

#if AQ_HAS_PAPER
uniform sampler2D u_paper;
#endif
uniform vec2 u_size;

void main() {
#if AQ_HAS_PAPER
  float h = texture(u_paper, gl_FragCoord.xy / u_size).r;
  h = h >= 0.0 ? min(h, 1.0) : 0.5;
#else
  float h = 0.5;
#endif
  o_threshold = vec4(layered_threshold(gl_FragCoord.xy), h, 0.0, 0.0);
}
