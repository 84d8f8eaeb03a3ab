// Pass 1 of `caustics`: for every vertex of the caustic grid (one fragment per vertex), the
// water surface height and analytic gradient, the refracted light direction, and where that
// ray meets the floor. Output: rg = floor displacement in tile widths, b = water height.
#include "aquarelle/noise.glsl"

uniform int u_grid;            // grid cells per tile side; this target is u_grid x u_grid
uniform float u_wave_scale;    // noise cells per tile of the first octave (whole number)
uniform float u_amplitude;     // water height amplitude, tile widths
uniform float u_depth;         // floor depth below the mean water level, tile widths
uniform float u_time_coord;    // speed * time, noise cells along the time axis
uniform float u_eta;           // n_air / n_water

layout(location = 0) out vec4 o_color;

const int kOctaves = 3;
const float kOctaveTimeOffset = 17.0;  // keeps the octaves' time slices unaligned at t = 0

void main() {
  vec2 p = floor(gl_FragCoord.xy) / float(u_grid);
  float height = 0.0;
  vec2 gradient = vec2(0.0);
  float total = 0.0;
  for (int k = 0; k < kOctaves; ++k) {
    float frequency = u_wave_scale * exp2(float(k));
    float weight = exp2(-float(k));
    vec4 n = aq_perlin3_with_gradient(
        vec3(p * frequency, exp2(float(k)) * u_time_coord + kOctaveTimeOffset * float(k)),
        vec3(frequency, frequency, 0.0));
    height += weight * n.x;
    // Chain rule: d/dx N(f x) = f N'(f x). Every octave adds the same slope scale.
    gradient += weight * frequency * n.yz;
    total += weight;
  }
  float a = u_amplitude / total;
  height *= a;
  gradient *= a;
  if (u_eta >= 1.0) {  // no refraction: exactly vertical rays, exactly flat light
    o_color = vec4(0.0, 0.0, height, 1.0);
    return;
  }
  vec3 normal = normalize(vec3(-gradient, 1.0));
  // eta <= 1 (air to water): no total internal reflection, t.z <= -sqrt(1 - eta^2) < 0.
  vec3 t = refract(vec3(0.0, 0.0, -1.0), normal, u_eta);
  float drop = max(u_depth + height, 0.0);
  vec2 displacement = t.z < 0.0 ? t.xy * (drop / -t.z) : vec2(0.0);
  o_color = vec4(displacement, height, 1.0);
}
