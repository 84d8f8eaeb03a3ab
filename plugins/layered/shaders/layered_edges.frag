// Wet-edge detection (seed 003) for four layers: the 3x3 Laplacian of the abstracted coverage,
// thresholded by a smooth step from edge_threshold to twice it. The noise threshold of the
// centre pixel serves its whole 3x3 neighbourhood (the noise is smooth at that scale).
layout(location = 0) out vec4 o_edges;

uniform sampler2D u_blurred;  // blurred intensities of the range
uniform float u_edge_threshold;

void main() {
  ivec2 p = ivec2(gl_FragCoord.xy);
  ivec2 last = textureSize(u_blurred, 0) - 1;
  float t = layered_threshold(gl_FragCoord.xy);
  vec4 n[9];
  for (int j = 0; j < 3; ++j) {
    for (int i = 0; i < 3; ++i) {
      vec4 b = texelFetch(u_blurred, clamp(p + ivec2(i - 1, j - 1), ivec2(0), last), 0);
      n[3 * j + i] = layered_abstract(b, t);
    }
  }
  vec4 r = aq_laplacian3x3(n);
  float th = max(u_edge_threshold, 1.0e-6);
  o_edges = smoothstep(vec4(th), vec4(2.0 * th), r);
}
