// pigment_apply's per-pixel function (aq_pointwise_desc): the three pigment densities of
// Bousseau et al. 2006 (seed 000 §3.6) read at the pixel from AQ_UNIFORM(density), the canvas
// `pigment_canvas` renders (r turbulence, g grain, b paper, each n + 0.5), applied in turn:
//     C ← C (1 − (1 − C)(d − 1)),  d = clamp(1 + weight · n, 0, 2)
// The node's own pass and the host's fused passes both call it; everything but the shared
// density formula stays inside AQ_APPLY, so two such stages can share one fused shader.
#include "aquarelle/pigment_density.glsl"

uniform sampler2D AQ_UNIFORM(density);
uniform vec3 AQ_UNIFORM(weights);  // turbulence, grain, paper

vec4 AQ_APPLY(vec4 c, vec2 pixel, vec2 size) {
  ivec2 density_size = textureSize(AQ_UNIFORM(density), 0);
  ivec2 p = clamp(ivec2(floor(pixel / size * vec2(density_size))), ivec2(0), density_size - 1);
  vec3 n = texelFetch(AQ_UNIFORM(density), p, 0).rgb - vec3(0.5);
  vec3 w = AQ_UNIFORM(weights);
  vec3 rgb = aq_pigment_density(c.rgb, w.x, n.x);
  rgb = aq_pigment_density(rgb, w.y, n.y);
  rgb = aq_pigment_density(rgb, w.z, n.z);
  return vec4(rgb, c.a);
}
