// `noise` texture: one periodic noise field over the whole texture, sampled at pixel centres.
// Texture-space units: u_cells lattice cells across the texture (a whole number per axis), so
// the pattern is the same at any resolution and repeats seamlessly.
#include "aquarelle/noise.glsl"

uniform vec2 u_size;    // output size in pixels
uniform vec2 u_cells;   // lattice cells across the texture per axis (the period)
uniform int u_type;     // 0 perlin, 1 fbm, 2 gaussian, 3 worley
uniform int u_octaves;  // fbm only
uniform int u_seed;
uniform int u_unit_range;  // 1: map to about [0,1]; 0: the raw value

layout(location = 0) out vec4 o_color;

void main() {
  vec2 p = gl_FragCoord.xy / u_size * u_cells;
  uint seed = uint(u_seed);
  float value;
  if (u_type == 0) {
    value = aq_perlin2_seeded(p, u_cells, seed);
    if (u_unit_range == 1) value = 0.5 + 0.5 * value;
  } else if (u_type == 1) {
    value = aq_fbm2_seeded(p, u_cells, u_octaves, seed);
    if (u_unit_range == 1) value = 0.5 + 0.5 * value;
  } else if (u_type == 2) {
    // One standard-normal sample per lattice cell (white noise at the cell size).
    vec2 cell = vec2(aq_wrap_cell(ivec2(floor(p)), u_cells));
    value = aq_gaussian_noise(cell, float(u_seed));
    if (u_unit_range == 1) value = clamp(0.5 + value / 6.0, 0.0, 1.0);  // +-3 sigma onto [0,1]
  } else {
    value = aq_worley2_seeded(p, u_cells, seed);
    if (u_unit_range == 1) value = min(value, 1.0);
  }
  o_color = vec4(vec3(value), 1.0);
}
