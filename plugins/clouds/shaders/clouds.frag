// Raymarched clouds / spray over the image (plugins/clouds/README.md). Along each camera ray,
// up to the g-buffer surface (depth test) or max_distance, midpoint steps accumulate the optical
// depth τ = Σ ρ(p_k) Δ of
//   ρ(p) = density · shape(p) · falloff(p)
//   shape = mix(1, n, noise), n = ½ + ½ fbm3((p − drift t) · scale); below threshold → 0
//   falloff: none 1 | height clamp((y − start)/length, 0, 1) | distance clamp(1 − |p − centre|/length, 0, 1)
// and the pixel becomes C · T + light · (1 − T), T = exp(−τ). τ = 0 returns C unchanged.
#include "aquarelle/noise.glsl"

in vec2 v_uv;
out vec4 o_color;

uniform sampler2D u_image;
uniform sampler2D u_depth;
uniform int u_has_depth;
uniform mat4 u_inverse_view_projection;
uniform vec3 u_camera;
uniform vec3 u_forward;
uniform float u_density;
uniform float u_noise;
uniform float u_scale;
uniform int u_octaves;
uniform float u_threshold;
uniform int u_falloff;  // 0 none, 1 height, 2 distance
uniform float u_falloff_start;
uniform float u_falloff_length;
uniform vec3 u_centre;
uniform vec3 u_drift;  // world units per second, already times the time
uniform vec3 u_light_color;
uniform int u_steps;
uniform float u_max_distance;

float density_at(vec3 p) {
  float shape = 1.0;
  if (u_noise > 0.0) {
    float n = 0.5 + 0.5 * aq_fbm3((p - u_drift) * u_scale, u_octaves);
    shape = mix(1.0, n, u_noise);
  }
  if (shape < u_threshold) return 0.0;  // the seed's stepped clouds
  float falloff = 1.0;
  if (u_falloff == 1) falloff = clamp((p.y - u_falloff_start) / u_falloff_length, 0.0, 1.0);
  if (u_falloff == 2) falloff = clamp(1.0 - length(p - u_centre) / u_falloff_length, 0.0, 1.0);
  return u_density * shape * falloff;
}

void main() {
  ivec2 px = ivec2(gl_FragCoord.xy);
  vec4 c = texelFetch(u_image, px, 0);
  ivec2 size = textureSize(u_image, 0);
  vec2 ndc = (vec2(px) + 0.5) / vec2(size) * 2.0 - 1.0;
  vec4 near_point = u_inverse_view_projection * vec4(ndc, -1.0, 1.0);
  vec4 far_point = u_inverse_view_projection * vec4(ndc, 1.0, 1.0);
  vec3 direction = normalize(far_point.xyz / far_point.w - near_point.xyz / near_point.w);
  float t_end = u_max_distance;
  if (u_has_depth != 0) {
    ivec2 dsize = textureSize(u_depth, 0);
    float depth = texelFetch(u_depth, min(px * dsize / size, dsize - 1), 0).r;
    float along = depth / max(dot(direction, u_forward), 1e-6);
    if (along >= 0.0) t_end = min(t_end, along);  // NaN depth: the full march
  }
  float step_length = t_end / float(u_steps);
  float tau = 0.0;
  for (int k = 0; k < u_steps; ++k) {
    tau += density_at(u_camera + (float(k) + 0.5) * step_length * direction);
  }
  tau *= step_length;
  if (!(tau > 0.0)) {
    o_color = c;
    return;
  }
  float transmittance = exp(-tau);
  o_color = vec4(c.rgb * transmittance + u_light_color * (1.0 - transmittance), c.a);
}
