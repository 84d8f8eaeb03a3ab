// `paper` height field: Worley grain (rounded pits between bumps, one bump per cell) layered
// with fBm fibres/cloudiness, as in seed 002. Periodic over the texture; sizes in texture units.
#include "aquarelle/noise.glsl"

uniform vec2 u_size;         // output size in pixels
uniform vec2 u_grain_cells;  // Worley cells across the texture per axis
uniform vec2 u_fiber_cells;  // fBm lattice cells across the texture per axis
uniform int u_octaves;
uniform float u_fiber_weight;  // 0: grain only, 1: fibres only
uniform float u_roughness;     // contrast around 0.5; 0 is flat paper
uniform int u_seed;

layout(location = 0) out vec4 o_color;

// The fibre field uses its own lattice so that it is independent of the grain's.
const uint kFiberSeedSalt = 0x68BC21EBu;

void main() {
  vec2 uv = gl_FragCoord.xy / u_size;
  uint seed = uint(u_seed);
  float grain = 1.0 - min(aq_worley2_seeded(uv * u_grain_cells, u_grain_cells, seed), 1.0);
  float fibers =
      0.5 + 0.5 * aq_fbm2_seeded(uv * u_fiber_cells, u_fiber_cells, u_octaves, seed ^ kFiberSeedSalt);
  float relief = mix(grain, fibers, u_fiber_weight) - 0.5;
  o_color = vec4(vec3(0.5 + u_roughness * relief), 1.0);
}
