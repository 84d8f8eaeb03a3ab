// Shared 3x3 edge kernels for plugin shaders: `#include "aquarelle/edge_kernels.glsl"`.
// Pure functions over a 3x3 neighbourhood n[9], row-major from the bottom-left (n[4] is the
// centre, n[3 * j + i] is the pixel at (i - 1, j - 1)). Each channel is filtered on its own.
//
//   aq_laplacian3x3: |sum of the 8 neighbours - 8 centre| (the underwater seed's "Sobel" kernel,
//                    -8 centre; seed 003's edge detection): 0 on a constant neighbourhood
//   aq_sobel3x3:     Sobel gradient magnitude sqrt(gx² + gy²)
//   aq_edge_weight:  the darkening weight of `edge` and `edge_detect` from either kernel
// Used by the `edge` and `layered` plugins; reference/edge.h has them in double. Guarded: a
// fused pass may hold two edge stages.
#ifndef AQ_EDGE_KERNELS_GLSL
#define AQ_EDGE_KERNELS_GLSL

vec3 aq_laplacian3x3(vec3 n[9]) {
  return abs(n[0] + n[1] + n[2] + n[3] + n[5] + n[6] + n[7] + n[8] - 8.0 * n[4]);
}
vec4 aq_laplacian3x3(vec4 n[9]) {
  return abs(n[0] + n[1] + n[2] + n[3] + n[5] + n[6] + n[7] + n[8] - 8.0 * n[4]);
}

vec3 aq_sobel3x3(vec3 n[9]) {
  vec3 gx = (n[2] + 2.0 * n[5] + n[8]) - (n[0] + 2.0 * n[3] + n[6]);
  vec3 gy = (n[6] + 2.0 * n[7] + n[8]) - (n[0] + 2.0 * n[1] + n[2]);
  return sqrt(gx * gx + gy * gy);
}
vec4 aq_sobel3x3(vec4 n[9]) {
  vec4 gx = (n[2] + 2.0 * n[5] + n[8]) - (n[0] + 2.0 * n[3] + n[6]);
  vec4 gy = (n[6] + 2.0 * n[7] + n[8]) - (n[0] + 2.0 * n[1] + n[2]);
  return sqrt(gx * gx + gy * gy);
}
// The edge-darkening weight of a 3x3 neighbourhood (the `edge` and `edge_detect` nodes):
// smoothstep(threshold, threshold + softness, response), the response the largest channel's
// Laplacian (or Sobel magnitude); a NaN response counts as 0, so it darkens nothing.
float aq_edge_weight(vec3 n[9], bool sobel, float threshold, float softness) {
  vec3 r = sobel ? aq_sobel3x3(n) : aq_laplacian3x3(n);
  float response = max(r.r, max(r.g, r.b));
  response = response >= 0.0 ? response : 0.0;
  return smoothstep(threshold, threshold + softness, response);
}
#endif  // AQ_EDGE_KERNELS_GLSL
