// Per-pixel blur strength s in [0, 1], shared by the composite and the strided shaders
// (prepended to them by blur.cpp). s = clamp(depth_weight · min(z / distance_scale, 1)³ +
// radial_weight · (|p - centre| / |corner - centre|)², 0, 1). Depth that is not a positive
// finite number (background, NaN) counts as far away; without a depth input the depth term
// is 1. blur.cpp defines AQ_HAS_DEPTH before this file, a compile-time switch (llvmpipe would
// evaluate both sides of a branch on a uniform): 0 no depth input, 1 depth the size of the
// image (read with texelFetch, which skips the filtering), 2 depth of another size (sampled).
#if AQ_HAS_DEPTH
uniform sampler2D u_depth;
#endif
uniform float u_distance_scale;
uniform float u_depth_weight;
uniform float u_radial_weight;
uniform vec2 u_size;  // output size in pixels

float blur_strength(vec2 frag) {
  float depth_term = 1.0;
#if AQ_HAS_DEPTH
#if AQ_HAS_DEPTH == 1
  float z = texelFetch(u_depth, ivec2(frag), 0).r;
#else
  float z = texture(u_depth, frag / u_size).r;
#endif
  float q = min(z / u_distance_scale, 1.0);
  depth_term = z > 0.0 && z <= 3.0e38 ? q * q * q : 1.0;
#endif
  vec2 from_centre = frag - 0.5 * u_size;
  // |p − centre|² / |corner − centre|², the corner at half the size from the centre.
  float radial_term = dot(from_centre, from_centre) * (4.0 / dot(u_size, u_size));
  return clamp(u_depth_weight * depth_term + u_radial_weight * radial_term, 0.0, 1.0);
}
