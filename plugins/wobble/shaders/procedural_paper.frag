// Procedural paper height in [0, 1] (Worley cells layered with fBm, as in seed 002), rendered
// once per paper pixel so that the wobble pass reads a texture either way. Coordinates are in
// paper pixels, so the paper looks the same at every output resolution.
#include "aquarelle/noise.glsl"

in vec2 v_uv;
layout(location = 0) out vec4 o_color;

uniform vec2 u_paper_size;  // paper pixels across the image
uniform float u_grain;      // Worley cell size in paper pixels
uniform vec2 u_seed_offset;

void main() {
  vec2 q = v_uv * u_paper_size / u_grain + u_seed_offset;
  float cells = 1.0 - min(aq_worley2(q, vec2(0.0)), 1.0);        // ridges between fibres: low
  float fibres = 0.5 + 0.5 * aq_fbm2(q * 0.37, vec2(0.0), 4);  // larger, softer undulation
  float height = clamp(0.6 * cells + 0.4 * fibres, 0.0, 1.0);
  o_color = vec4(vec3(height), 1.0);
}
