// Pass 3 of `caustics` with the `coverage` estimator: counts of light to intensity. Flat water
// would have given `u_flat_counts`; the intensity is 1 plus the difference, scaled so that one
// texel's worth of light is 1. The differences sum to exactly 0 over the tile (every triangle
// gives out the same whole number of counts either way), so the mean is 1 to float rounding,
// and flat water gives exactly 1.
uniform usampler2D u_counts;
uniform usampler2D u_flat_counts;
uniform float u_intensity_per_count;

layout(location = 0) out vec4 o_color;

void main() {
  ivec2 texel = ivec2(gl_FragCoord.xy);
  uint counts = texelFetch(u_counts, texel, 0).r;
  uint flat_counts = texelFetch(u_flat_counts, texel, 0).r;
  // Both are at most 2^31 - 1: the difference fits an int.
  float intensity = 1.0 + float(int(counts - flat_counts)) * u_intensity_per_count;
  o_color = vec4(vec3(max(intensity, 0.0)), 1.0);
}
