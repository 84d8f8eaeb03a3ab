// Paper relief (plugins/paper_relief/README.md) as the node's per-pixel function: the painted
// image, with the paper colour showing through diluted areas, lit as a bump map by the paper
// height's central-difference normal:
//   base  = mix(C, paper_colour, clamp(show · m, 0, 1))
//   N     = normalize(−bump · ∂h/∂x, −bump · ∂h/∂y, 1),  s = max(N·L, 0) / L.z
//   out   = base · (1 + relief · (s − 1))        flat paper: s = 1 exactly, out = base
// The node's own pass and the host's fused passes both call it (aq_pointwise_desc): the colour
// is the image at the pixel, paper and mask samplers read at the pixel under it (the paper one
// pixel around). Everything stays inside AQ_APPLY (no helper functions but the guarded library's),
// so two relief stages can share one fused shader.
#include "aquarelle/integer_division.glsl"
uniform sampler2D AQ_UNIFORM(paper);  // height in r
uniform sampler2D AQ_UNIFORM(mask);   // how much paper shows, in r
uniform int AQ_UNIFORM(has_mask);
uniform vec3 AQ_UNIFORM(light);  // unit, towards the light, z > 0
uniform vec3 AQ_UNIFORM(paper_color);
uniform float AQ_UNIFORM(bump);
uniform float AQ_UNIFORM(relief);
uniform float AQ_UNIFORM(show);

vec4 AQ_APPLY(vec4 c, vec2 pixel, vec2 size) {
  ivec2 p = ivec2(floor(pixel));
  ivec2 image_size = ivec2(size);
  vec3 base = c.rgb;
  if (AQ_UNIFORM(has_mask) != 0) {
    ivec2 mask_size = textureSize(AQ_UNIFORM(mask), 0);
    ivec2 under = min(aq_scaled_texel(p, image_size, mask_size), mask_size - 1);
    float m = texelFetch(AQ_UNIFORM(mask), under, 0).r;
    if (isnan(m)) m = 0.0;
    float show = clamp(AQ_UNIFORM(show) * m, 0.0, 1.0);
    if (show > 0.0) base = mix(base, AQ_UNIFORM(paper_color), show);
  }
  ivec2 paper_size = textureSize(AQ_UNIFORM(paper), 0);
  ivec2 last = paper_size - 1;
  ivec2 q = aq_scaled_texel(p, image_size, paper_size);
  float dx = 0.5 * (texelFetch(AQ_UNIFORM(paper), clamp(q + ivec2(1, 0), ivec2(0), last), 0).r -
                    texelFetch(AQ_UNIFORM(paper), clamp(q - ivec2(1, 0), ivec2(0), last), 0).r);
  float dy = 0.5 * (texelFetch(AQ_UNIFORM(paper), clamp(q + ivec2(0, 1), ivec2(0), last), 0).r -
                    texelFetch(AQ_UNIFORM(paper), clamp(q - ivec2(0, 1), ivec2(0), last), 0).r);
  if (isnan(dx) || isinf(dx)) dx = 0.0;
  if (isnan(dy) || isinf(dy)) dy = 0.0;
  vec3 n = normalize(vec3(-AQ_UNIFORM(bump) * dx, -AQ_UNIFORM(bump) * dy, 1.0));
  // Flat paper is exactly unlit (s = 1), whatever the division's rounding.
  float s = dx == 0.0 && dy == 0.0 ? 1.0
                                   : max(dot(n, AQ_UNIFORM(light)), 0.0) / AQ_UNIFORM(light).z;
  return vec4(s == 1.0 ? base : base * (1.0 + AQ_UNIFORM(relief) * (s - 1.0)), c.a);
}
