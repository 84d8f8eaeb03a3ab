// Shared by the layered passes (prepended by layered.cpp after its #defines): the
// noise-modulated abstraction threshold and the ease-out curve. README.md has the maths.
#include "aquarelle/noise.glsl"

uniform float u_threshold;    // abstraction: level of the blurred mask where the edge lies
uniform float u_softness;     // half-width of the smooth step around it
uniform float u_edge_noise;   // amplitude of the threshold's modulation (edge position)
uniform float u_noise_scale;  // pixels per noise lattice cell

float layered_threshold(vec2 frag) {
  if (!(u_edge_noise > 0.0)) return u_threshold;
  return u_threshold + u_edge_noise * aq_fbm2(frag / u_noise_scale, vec2(0.0), 3);
}

// The abstracted coverage of blurred masks `b` with threshold t: smoothstep(t - s, t + s, b).
vec4 layered_abstract(vec4 b, float t) {
  float s = max(u_softness, 1.0e-4);
  return smoothstep(vec4(t - s), vec4(t + s), b);
}

vec4 layered_ease_out(vec4 x) {
  vec4 c = clamp(x, 0.0, 1.0);
  return 1.0 - (1.0 - c) * (1.0 - c);
}
