// Wet-edge detection of the `fast` method at half resolution: the 3x3 Laplacian of each
// listed layer's abstracted coverage, thresholded (as layered_edges.frag), times u_scale: a
// band one texel wide here is two pixels wide at full size, twice the pigment a full-size
// band of the same texels would put down after the blur.
layout(location = 0) out vec4 o_edges;

uniform sampler2D u_keys;     // the blurred lists' keys
uniform sampler2D u_blurred;  // their blurred intensities
uniform float u_edge_threshold;
uniform float u_scale;

void main() {
  ivec2 p = ivec2(gl_FragCoord.xy);
  ivec2 size = textureSize(u_keys, 0);
  vec4 keys = texelFetch(u_keys, p, 0);
  float t = layered_threshold(float(AQ_DIVISOR) * gl_FragCoord.xy);  // the full-size pixel position
  vec4 n[9];
  for (int j = 0; j < 3; ++j) {
    for (int i = 0; i < 3; ++i) {
      ivec2 q = list_clamp(p + ivec2(i - 1, j - 1), size);
      vec4 b = list_match(keys, texelFetch(u_keys, q, 0)) * texelFetch(u_blurred, q, 0);
      n[3 * j + i] = layered_abstract(b, t);
    }
  }
  vec4 r = aq_laplacian3x3(n);
  float th = max(u_edge_threshold, 1.0e-6);
  o_edges = u_scale * smoothstep(vec4(th), vec4(2.0 * th), r) * vec4(greaterThan(keys, vec4(0.5)));
}
