// The march of the clouds / spray (plugins/clouds/README.md), one ray per cell of `resolution`²
// output pixels (the ray through the cell's centre pixel, stopped at that pixel's surface).
// Outputs (τ, the segment's end depth, 0, 0); clouds_composite.frag upsamples τ by depth.
//   ρ(p) = density · shape(p) · falloff(p)
//   shape = mix(1, n, noise), n = ½ + ½ fbm3((p − drift t) · scale); below threshold → 0
//   falloff: none 1 | height clamp((y − start)/length, 0, 1) |
//            distance clamp(1 − (|p − centre| + warp · fbm3(animated)) / length, 0, 1)
// τ = Σ ρ(p_k) Δ by midpoint steps over the part of the ray where the falloff can be non-zero
// (above the height ramp's start; inside the distance falloff's sphere, widened by the warp):
// outside it the density is exactly 0, so clipping the march there is no approximation, and a
// ray that never enters it (or meets the scene first) costs nothing.
#include "aquarelle/noise.glsl"
#include "aquarelle/integer_division.glsl"

in vec2 v_uv;
layout(location = 0) out vec4 o_tau;

uniform sampler2D u_depth;
uniform int u_has_depth;
uniform ivec2 u_size;  // the output's size in pixels
uniform int u_cell;    // output pixels per march cell, along each axis
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
uniform vec3 u_drift;  // world units, already times the time
uniform float u_warp;  // world units the distance falloff is pushed by animated FBM
uniform float u_time;
uniform int u_steps;
uniform float u_max_distance;

float density_at(vec3 p) {
  float falloff = 1.0;
  if (u_falloff == 1) falloff = clamp((p.y - u_falloff_start) / u_falloff_length, 0.0, 1.0);
  if (u_falloff == 2) {
    float distance = length(p - u_centre);
    if (u_warp > 0.0) {
      // The spray's edge distorted by FBM animated along all three axes (seed 002's waterfall).
      vec3 q = p * (0.5 * u_scale) + u_time * vec3(0.31, -0.47, 0.23) + vec3(5.2, 1.3, 7.7);
      distance += u_warp * aq_fbm3(q, 2);
    }
    falloff = clamp(1.0 - distance / u_falloff_length, 0.0, 1.0);
  }
  if (falloff <= 0.0) return 0.0;
  float shape = 1.0;
  if (u_noise > 0.0) {
    float n = 0.5 + 0.5 * aq_fbm3((p - u_drift) * u_scale, u_octaves);
    shape = mix(1.0, n, u_noise);
  }
  if (shape < u_threshold) return 0.0;  // the seed's stepped clouds
  return u_density * shape * falloff;
}

// The part [t0, t1] of the ray o + t d, 0 <= t <= t_end, where the falloff may be non-zero.
vec2 live_segment(vec3 o, vec3 d, float t_end) {
  float t0 = 0.0, t1 = t_end;
  if (u_falloff == 1) {
    if (abs(d.y) < 1e-12) {
      if (o.y <= u_falloff_start) t1 = -1.0;
    } else {
      float t = (u_falloff_start - o.y) / d.y;
      if (d.y > 0.0) t0 = max(t0, t); else t1 = min(t1, t);
    }
  } else if (u_falloff == 2) {
    float radius = u_falloff_length + max(u_warp, 0.0) * 1.05;  // |fbm3| <= 1 (and rounding)
    vec3 oc = o - u_centre;
    float b = dot(oc, d);
    float disc = b * b - (dot(oc, oc) - radius * radius);
    if (!(disc > 0.0)) return vec2(0.0, -1.0);
    float r = sqrt(disc);
    t0 = max(t0, -b - r);
    t1 = min(t1, -b + r);
  }
  return vec2(t0, t1);
}

void main() {
  ivec2 cell = ivec2(gl_FragCoord.xy);
  ivec2 px = min(cell * u_cell + u_cell / 2, u_size - 1);  // the cell's centre pixel
  vec2 ndc = (vec2(px) + 0.5) / vec2(u_size) * 2.0 - 1.0;
  vec4 near_point = u_inverse_view_projection * vec4(ndc, -1.0, 1.0);
  vec4 far_point = u_inverse_view_projection * vec4(ndc, 1.0, 1.0);
  vec3 direction = normalize(far_point.xyz / far_point.w - near_point.xyz / near_point.w);
  float t_end = u_max_distance;
  float depth = u_max_distance;
  if (u_has_depth != 0) {
    ivec2 dsize = textureSize(u_depth, 0);
    depth = texelFetch(u_depth, min(aq_scaled_texel(px, u_size, dsize), dsize - 1), 0).r;
    float along = depth / max(dot(direction, u_forward), 1e-6);
    if (along >= 0.0) t_end = min(t_end, along);  // NaN depth: the full march
  }
  // The view depth the composite compares with its own pixel's (far surfaces: max_distance).
  float end_depth = depth >= 0.0 ? min(depth, u_max_distance) : u_max_distance;
  vec2 segment = live_segment(u_camera, direction, t_end);
  float tau = 0.0;
  if (segment.y > segment.x) {
    float step_length = (segment.y - segment.x) / float(u_steps);
    for (int k = 0; k < u_steps; ++k) {
      tau += density_at(u_camera + (segment.x + (float(k) + 0.5) * step_length) * direction);
    }
    tau *= step_length;
  }
  o_tau = vec4(tau, end_depth, 0.0, 0.0);
}
