// Shared procedural noise for plugin shaders: `#include "aquarelle/noise.glsl"`.
//
// Every function is pure (no uniforms, no textures) and built on integer hashes (PCG2D/PCG3D,
// Jarzynski & Olano, "Hash Functions for GPU Rendering", JCGT 2020), so a given input gives the
// same lattice values on every GPU; only the final float arithmetic (fade curves, sqrt, log, cos)
// is subject to the usual GLSL precision rules. reference/noise_reference.h implements the
// same definitions in double precision on the CPU.
//
// Lattice cells are the integer parts floor(p). Periods are in lattice cells and must be whole
// numbers (they are rounded); a period component <= 0 means "not periodic along this axis".
// Wrapping is applied to the cell index before hashing, so a periodic function repeats exactly.
// aq_perlin2, aq_fbm2 and aq_worley2 have `_seeded(..., uint seed)` variants giving independent
// fields per seed; the unseeded names are seed 0.

// ---- Hashes --------------------------------------------------------------------------------

uvec2 aq_pcg2d(uvec2 v) {
  v = v * 1664525u + 1013904223u;
  v.x += v.y * 1664525u;
  v.y += v.x * 1664525u;
  v = v ^ (v >> 16u);
  v.x += v.y * 1664525u;
  v.y += v.x * 1664525u;
  v = v ^ (v >> 16u);
  return v;
}

uvec3 aq_pcg3d(uvec3 v) {
  v = v * 1664525u + 1013904223u;
  v.x += v.y * v.z;
  v.y += v.z * v.x;
  v.z += v.x * v.y;
  v ^= v >> 16u;
  v.x += v.y * v.z;
  v.y += v.z * v.x;
  v.z += v.x * v.y;
  return v;
}

// Top 24 bits of a hash as a float in [0,1); exact in single precision.
float aq_unit_float(uint h) { return float(h >> 8u) * (1.0 / 16777216.0); }

// Cell index of p, wrapped into [0, period) when period > 0 (sign-safe integer modulo).
int aq_wrap_cell(int cell, float period) {
  int n = int(round(period));
  if (n <= 0) return cell;
  int m = cell - n * int(floor(float(cell) / float(n)));
  if (m < 0) m += n;
  if (m >= n) m -= n;
  return m;
}
ivec2 aq_wrap_cell(ivec2 cell, vec2 period) {
  return ivec2(aq_wrap_cell(cell.x, period.x), aq_wrap_cell(cell.y, period.y));
}
ivec3 aq_wrap_cell(ivec3 cell, vec3 period) {
  return ivec3(aq_wrap_cell(cell.x, period.x), aq_wrap_cell(cell.y, period.y),
               aq_wrap_cell(cell.z, period.z));
}

// Hash of the integer cell floor(p), in [0,1).
float aq_hash12(vec2 p) { return aq_unit_float(aq_pcg2d(uvec2(ivec2(floor(p)))).x); }

// Two independent values in [0,1) for the integer cell floor(p).
vec2 aq_hash22(vec2 p) {
  uvec2 h = aq_pcg2d(uvec2(ivec2(floor(p))));
  return vec2(aq_unit_float(h.x), aq_unit_float(h.y));
}

// ---- Gradient (Perlin) noise ---------------------------------------------------------------

// Perlin's quintic fade 6t^5 - 15t^4 + 10t^3 and its derivative.
vec2 aq_fade(vec2 t) { return t * t * t * (t * (t * 6.0 - 15.0) + 10.0); }
vec3 aq_fade(vec3 t) { return t * t * t * (t * (t * 6.0 - 15.0) + 10.0); }
vec3 aq_fade_derivative(vec3 t) { return 30.0 * t * t * (t * (t - 2.0) + 1.0); }

// One of 8 unit gradients, k * 45 degrees for k = hash of (cell, seed) & 7: the base (1, 0) or
// (d, d) by the parity of k, turned by 90 degrees (k >> 1) times. Selects, not a table (see
// aq_perlin3_gradient).
vec2 aq_perlin2_gradient(ivec2 cell, uint seed) {
  const float d = 0.70710678118654752;
  uint k = aq_pcg3d(uvec3(uvec2(cell), seed)).x & 7u;
  vec2 g = (k & 1u) == 0u ? vec2(1.0, 0.0) : vec2(d, d);
  uint quarter_turns = k >> 1u;
  if ((quarter_turns & 1u) != 0u) g = vec2(-g.y, g.x);
  if ((quarter_turns & 2u) != 0u) g = -g;
  return g;
}

// 2D gradient noise, periodic with `period` cells per axis (0 = not periodic). The sum of the
// four corner ramps is scaled by sqrt(2) so that the range is [-1,1] (the unscaled extreme of
// 2D Perlin noise with unit gradients is sqrt(2)/2). Each seed gives an independent field.
float aq_perlin2_seeded(vec2 p, vec2 period, uint seed) {
  ivec2 i = ivec2(floor(p));
  vec2 f = p - floor(p);
  float n00 = dot(aq_perlin2_gradient(aq_wrap_cell(i, period), seed), f);
  float n10 = dot(aq_perlin2_gradient(aq_wrap_cell(i + ivec2(1, 0), period), seed), f - vec2(1, 0));
  float n01 = dot(aq_perlin2_gradient(aq_wrap_cell(i + ivec2(0, 1), period), seed), f - vec2(0, 1));
  float n11 = dot(aq_perlin2_gradient(aq_wrap_cell(i + ivec2(1, 1), period), seed), f - vec2(1, 1));
  vec2 u = aq_fade(f);
  return 1.41421356237309505 * mix(mix(n00, n10, u.x), mix(n01, n11, u.x), u.y);
}

float aq_perlin2(vec2 p, vec2 period) { return aq_perlin2_seeded(p, period, 0u); }

// One of Perlin's 12 cube-edge gradients (length sqrt(2)) from the low 4 bits h of the cell's
// hash, 16 entries with 4 repeated as in Perlin's "Improving Noise" (2002):
//   h = 0..3: (+-1, +-1, 0), 4..7: (+-1, 0, +-1), 8..11: (0, +-1, +-1) with the first sign
//   from bit 0 and the second from bit 1; h = 12, 13, 14, 15 repeat h = 0, 1, 9, 11.
// Computed with selects rather than a table: dynamic indexing of a constant array is slow to
// compile and to run on llvmpipe.
vec3 aq_perlin3_gradient(ivec3 cell) {
  uint h = aq_pcg3d(uvec3(cell)).x & 15u;
  if (h >= 12u) h = h == 12u ? 0u : h == 13u ? 1u : h == 14u ? 9u : 11u;
  float a = (h & 1u) == 0u ? 1.0 : -1.0;
  float b = (h & 2u) == 0u ? 1.0 : -1.0;
  uint group = h >> 2u;
  return group == 0u ? vec3(a, b, 0.0) : group == 1u ? vec3(a, 0.0, b) : vec3(0.0, a, b);
}

// 3D gradient noise with its analytic gradient: returns vec4(value, d/dx, d/dy, d/dz).
// Range of the value is about [-1,1]. Periodic per axis as aq_perlin2.
vec4 aq_perlin3_with_gradient(vec3 p, vec3 period) {
  ivec3 i = ivec3(floor(p));
  vec3 f = p - floor(p);
  vec3 g000 = aq_perlin3_gradient(aq_wrap_cell(i + ivec3(0, 0, 0), period));
  vec3 g100 = aq_perlin3_gradient(aq_wrap_cell(i + ivec3(1, 0, 0), period));
  vec3 g010 = aq_perlin3_gradient(aq_wrap_cell(i + ivec3(0, 1, 0), period));
  vec3 g110 = aq_perlin3_gradient(aq_wrap_cell(i + ivec3(1, 1, 0), period));
  vec3 g001 = aq_perlin3_gradient(aq_wrap_cell(i + ivec3(0, 0, 1), period));
  vec3 g101 = aq_perlin3_gradient(aq_wrap_cell(i + ivec3(1, 0, 1), period));
  vec3 g011 = aq_perlin3_gradient(aq_wrap_cell(i + ivec3(0, 1, 1), period));
  vec3 g111 = aq_perlin3_gradient(aq_wrap_cell(i + ivec3(1, 1, 1), period));
  float v000 = dot(g000, f - vec3(0, 0, 0));
  float v100 = dot(g100, f - vec3(1, 0, 0));
  float v010 = dot(g010, f - vec3(0, 1, 0));
  float v110 = dot(g110, f - vec3(1, 1, 0));
  float v001 = dot(g001, f - vec3(0, 0, 1));
  float v101 = dot(g101, f - vec3(1, 0, 1));
  float v011 = dot(g011, f - vec3(0, 1, 1));
  float v111 = dot(g111, f - vec3(1, 1, 1));
  vec3 u = aq_fade(f);
  vec3 du = aq_fade_derivative(f);
  // Trilinear blend written as a polynomial in u so that it can be differentiated directly.
  float k0 = v000;
  float k1 = v100 - v000;
  float k2 = v010 - v000;
  float k3 = v001 - v000;
  float k4 = v000 - v100 - v010 + v110;
  float k5 = v000 - v010 - v001 + v011;
  float k6 = v000 - v100 - v001 + v101;
  float k7 = -v000 + v100 + v010 - v110 + v001 - v101 - v011 + v111;
  vec3 c0 = g000;
  vec3 c1 = g100 - g000;
  vec3 c2 = g010 - g000;
  vec3 c3 = g001 - g000;
  vec3 c4 = g000 - g100 - g010 + g110;
  vec3 c5 = g000 - g010 - g001 + g011;
  vec3 c6 = g000 - g100 - g001 + g101;
  vec3 c7 = -g000 + g100 + g010 - g110 + g001 - g101 - g011 + g111;
  float value = k0 + k1 * u.x + k2 * u.y + k3 * u.z + k4 * u.x * u.y + k5 * u.y * u.z +
                k6 * u.z * u.x + k7 * u.x * u.y * u.z;
  vec3 gradient = c0 + c1 * u.x + c2 * u.y + c3 * u.z + c4 * u.x * u.y + c5 * u.y * u.z +
                  c6 * u.z * u.x + c7 * u.x * u.y * u.z +
                  du * vec3(k1 + k4 * u.y + k6 * u.z + k7 * u.y * u.z,
                            k2 + k4 * u.x + k5 * u.z + k7 * u.x * u.z,
                            k3 + k5 * u.y + k6 * u.x + k7 * u.x * u.y);
  return vec4(value, gradient);
}

float aq_perlin3(vec3 p, vec3 period) { return aq_perlin3_with_gradient(p, period).x; }

// Fractal sum of `octaves` (>= 1) layers of aq_perlin2: octave k has frequency 2^k, period
// period * 2^k (so every octave keeps the same period in p), amplitude 2^-k and its own
// lattice (seed + k * 0x9E3779B9). The sum is divided by the total amplitude
// (2 - 2^(1-octaves)) so the range stays about [-1,1].
float aq_fbm2_seeded(vec2 p, vec2 period, int octaves, uint seed) {
  float sum = 0.0;
  float amplitude = 1.0;
  float total = 0.0;
  float frequency = 1.0;
  for (int k = 0; k < max(octaves, 1); ++k) {
    sum += amplitude * aq_perlin2_seeded(p * frequency, period * frequency,
                                         seed + uint(k) * 0x9E3779B9u);
    total += amplitude;
    amplitude *= 0.5;
    frequency *= 2.0;
  }
  return sum / total;
}

float aq_fbm2(vec2 p, vec2 period, int octaves) { return aq_fbm2_seeded(p, period, octaves, 0u); }

// ---- Value noises --------------------------------------------------------------------------

// A standard-normal sample per integer cell floor(cell), for a given seed (Box-Muller on two
// 24-bit hashes; u1 in (0,1] so the logarithm is finite and |value| <= 5.8).
float aq_gaussian_noise(vec2 cell, float seed) {
  uvec3 h = aq_pcg3d(uvec3(uvec2(ivec2(floor(cell))), floatBitsToUint(seed)));
  float u1 = (float(h.x >> 8u) + 1.0) * (1.0 / 16777216.0);
  float u2 = aq_unit_float(h.y);
  return sqrt(-2.0 * log(u1)) * cos(6.28318530717958648 * u2);
}

// Worley (cellular) noise F1: Euclidean distance from p to the nearest feature point, one
// feature point per cell at cell + two 24-bit hashes of (wrapped cell, seed). Periodic with
// `period` cells.
// The own cell's point is closer than sqrt(2), so the search covers the 5x5 neighbourhood
// minus its corners (which are always farther than sqrt(2)): the result is the exact F1, not
// the usual 3x3 approximation. Range [0, sqrt(2)), typically below 1.
float aq_worley2_seeded(vec2 p, vec2 period, uint seed) {
  ivec2 i = ivec2(floor(p));
  vec2 f = p - floor(p);
  float nearest = 1e9;
  for (int y = -2; y <= 2; ++y) {
    for (int x = -2; x <= 2; ++x) {
      if (abs(x) == 2 && abs(y) == 2) continue;
      ivec2 offset = ivec2(x, y);
      uvec3 h = aq_pcg3d(uvec3(uvec2(aq_wrap_cell(i + offset, period)), seed));
      vec2 feature = vec2(offset) + vec2(aq_unit_float(h.x), aq_unit_float(h.y));
      nearest = min(nearest, length(feature - f));
    }
  }
  return nearest;
}

float aq_worley2(vec2 p, vec2 period) { return aq_worley2_seeded(p, period, 0u); }

// Fractal sum of `octaves` (>= 1) layers of non-periodic aq_perlin3: octave k has frequency
// 2^k, amplitude 2^-k and is shifted by k * (17.13, 31.71, 47.37) so the octaves' lattices do
// not line up at the origin; divided by the total amplitude (range about [-1,1]). Used for
// object-space variation (seed 002: control maps, dilution turbulence, clouds).
// Seed 002's cubism: aq_perlin3 (not periodic) with each axis's blend weight
// smoothstep(bend/2, 1 − bend/2, t) instead of Perlin's fade, the smoothstep called with the
// wrong edges as in the seed's "accident": with bend near 1 the blend is a step in the middle
// of each lattice cell, so the noise breaks into flat-faced blocks. bend in (0, 0.95].
float aq_perlin3_bent(vec3 p, float bend) {
  ivec3 i = ivec3(floor(p));
  vec3 f = p - floor(p);
  vec3 u = smoothstep(vec3(0.5 * bend), vec3(1.0 - 0.5 * bend), f);
  float v[8];
  for (int c = 0; c < 8; ++c) {
    ivec3 corner = ivec3(c & 1, (c >> 1) & 1, (c >> 2) & 1);
    v[c] = dot(aq_perlin3_gradient(i + corner), f - vec3(corner));
  }
  float x0 = mix(v[0], v[1], u.x), x1 = mix(v[2], v[3], u.x);
  float x2 = mix(v[4], v[5], u.x), x3 = mix(v[6], v[7], u.x);
  return mix(mix(x0, x1, u.y), mix(x2, x3, u.y), u.z);
}

// aq_fbm3 over aq_perlin3_bent (the same octaves, offsets and normalisation).
float aq_fbm3_bent(vec3 p, int octaves, float bend) {
  float sum = 0.0;
  float amplitude = 1.0;
  float total = 0.0;
  float frequency = 1.0;
  for (int k = 0; k < max(octaves, 1); ++k) {
    sum += amplitude * aq_perlin3_bent(p * frequency + float(k) * vec3(17.13, 31.71, 47.37), bend);
    total += amplitude;
    amplitude *= 0.5;
    frequency *= 2.0;
  }
  return sum / total;
}

float aq_fbm3(vec3 p, int octaves) {
  float sum = 0.0;
  float amplitude = 1.0;
  float total = 0.0;
  float frequency = 1.0;
  for (int k = 0; k < max(octaves, 1); ++k) {
    sum += amplitude * aq_perlin3(p * frequency + float(k) * vec3(17.13, 31.71, 47.37), vec3(0.0));
    total += amplitude;
    amplitude *= 0.5;
    frequency *= 2.0;
  }
  return sum / total;
}
