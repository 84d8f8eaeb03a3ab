// Edge darkening (seed sec. 3.5 and sec. 7.3) as the node's per-pixel function: edges are
// detected on AQ_UNIFORM(source) (the effect-free image when the node's `source` input is
// connected, else the image itself) with the 3x3 Laplacian (-8 centre, the seed's "Sobel"
// kernel) or the Sobel gradient magnitude; the response is the largest over r, g, b. The
// colour's HSV value is scaled towards `factor` by a smoothstep of the response. Scaling V with
// H and S fixed is scaling r, g and b by the same number, so no HSV round trip is needed.
//
// The node's own pass and the host's fused passes both call it (aq_pointwise_desc): the colour
// is the image at the pixel, the source a sampler read around it. Everything but the shared,
// include-guarded aq_edge_weight (also edge_detect's) stays inside AQ_APPLY, so two edge stages
// can share one fused shader.
#include "aquarelle/edge_kernels.glsl"

uniform sampler2D AQ_UNIFORM(source);
uniform float AQ_UNIFORM(factor);
uniform float AQ_UNIFORM(threshold);
uniform float AQ_UNIFORM(softness);
uniform int AQ_UNIFORM(sobel);  // 1: Sobel; both kernels share the 9 reads, so a uniform is cheap

vec4 AQ_APPLY(vec4 c, vec2 pixel, vec2 size) {
  ivec2 source_size = textureSize(AQ_UNIFORM(source), 0);
  ivec2 p = ivec2(floor(pixel / size * vec2(source_size)));
  ivec2 last = source_size - 1;
  vec3 n[9];  // row-major from bottom-left: n[4] is the centre
  for (int j = 0; j < 3; ++j) {
    for (int i = 0; i < 3; ++i) {
      n[3 * j + i] =
          texelFetch(AQ_UNIFORM(source), clamp(p + ivec2(i - 1, j - 1), ivec2(0), last), 0).rgb;
    }
  }
  float edge = aq_edge_weight(n, AQ_UNIFORM(sobel) == 1, AQ_UNIFORM(threshold),
                              AQ_UNIFORM(softness));
  return vec4(c.rgb * mix(1.0, AQ_UNIFORM(factor), edge), c.a);
}
