// edge_detect: the darkening weight `edge` computes per pixel, on its own (aq_edge_weight,
// aquarelle/edge_kernels.glsl): smoothstep(threshold, threshold + softness, response) of the
// 3x3 Laplacian (-8 centre) or Sobel response of the source, the largest over r, g, b; borders
// clamp to the edge. One output pixel per source pixel.
#include "aquarelle/edge_kernels.glsl"

uniform sampler2D u_source;
uniform float u_threshold;
uniform float u_softness;
uniform int u_sobel;  // 1: Sobel; both kernels share the 9 reads

layout(location = 0) out vec4 o_weight;

void main() {
  ivec2 p = ivec2(gl_FragCoord.xy);
  ivec2 last = textureSize(u_source, 0) - 1;
  vec3 n[9];  // row-major from bottom-left: n[4] is the centre
  for (int j = 0; j < 3; ++j) {
    for (int i = 0; i < 3; ++i) {
      n[3 * j + i] = texelFetch(u_source, clamp(p + ivec2(i - 1, j - 1), ivec2(0), last), 0).rgb;
    }
  }
  o_weight = vec4(aq_edge_weight(n, u_sobel == 1, u_threshold, u_softness), 0.0, 0.0, 1.0);
}
