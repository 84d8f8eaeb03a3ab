// Per-pixel blur strength s in [0, 1], shared by the composite and the strided shaders
// (prepended to them by blur.cpp). s = clamp(depth_weight · min(z / distance_scale, 1)³ +
// radial_weight · (|p - centre| / |corner - centre|)², 0, 1). Depth that is not a positive
// finite number (background, NaN) counts as far away; without a depth input the depth term
// is 1.
uniform sampler2D u_depth;
uniform bool u_has_depth;
uniform float u_distance_scale;
uniform float u_depth_weight;
uniform float u_radial_weight;
uniform vec2 u_size;  // output size in pixels

float blur_strength(vec2 frag) {
  float depth_term = 1.0;
  if (u_has_depth) {
    float z = texture(u_depth, frag / u_size).r;
    if (z > 0.0 && z <= 3.0e38) {
      float q = min(z / u_distance_scale, 1.0);
      depth_term = q * q * q;
    }
  }
  vec2 from_centre = frag - 0.5 * u_size;
  vec2 corner = 0.5 * u_size;
  float radial_term = dot(from_centre, from_centre) / dot(corner, corner);
  return clamp(u_depth_weight * depth_term + u_radial_weight * radial_term, 0.0, 1.0);
}
