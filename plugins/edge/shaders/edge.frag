// Edge darkening (seed sec. 3.5 and sec. 7.3). Edges are detected on u_source (the effect-free image
// when the node's `source` input is connected, else the image itself) with the 3x3 Laplacian
// (-8 centre, the seed's "Sobel" kernel) or the Sobel gradient magnitude; the response is the
// largest over r, g, b. The image's HSV value is scaled towards `factor` by a smoothstep of the
// response. Scaling V with H and S fixed is scaling r, g and b by the same number, so no HSV
// round trip (and its rounding) is needed.
#include "aquarelle/edge_kernels.glsl"
in vec2 v_uv;
layout(location = 0) out vec4 o_color;

uniform sampler2D u_image;
uniform sampler2D u_source;
// The node defines AQ_EDGE_SOBEL for the Sobel variant (llvmpipe would run both kernels if the
// choice were a branch on a uniform).
uniform float u_factor;
uniform float u_threshold;
uniform float u_softness;

vec3 source_at(ivec2 p) {
  ivec2 last = textureSize(u_source, 0) - 1;
  return texelFetch(u_source, clamp(p, ivec2(0), last), 0).rgb;
}

float edge_response(ivec2 p) {
  vec3 n[9];  // row-major from bottom-left: n[4] is the centre
  for (int j = 0; j < 3; ++j) {
    for (int i = 0; i < 3; ++i) n[3 * j + i] = source_at(p + ivec2(i - 1, j - 1));
  }
#ifdef AQ_EDGE_SOBEL
  vec3 r = aq_sobel3x3(n);
#else
  vec3 r = aq_laplacian3x3(n);
#endif
  float response = max(r.r, max(r.g, r.b));
  // A NaN in the source must not darken (or poison) its neighbours.
  return response >= 0.0 ? response : 0.0;
}

void main() {
  vec4 color = texelFetch(u_image, ivec2(gl_FragCoord.xy), 0);
  ivec2 source_pixel = ivec2(floor(v_uv * vec2(textureSize(u_source, 0))));
  float edge = smoothstep(u_threshold, u_threshold + u_softness, edge_response(source_pixel));
  o_color = vec4(color.rgb * mix(1.0, u_factor, edge), color.a);
}
