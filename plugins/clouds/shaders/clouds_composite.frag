// The volume over the image (plugins/clouds/README.md): τ of the march cells upsampled by depth
// (joint bilateral: the four nearest cells' bilinear weights times how close the depth their
// ray ended at is to this pixel's), then C · T + light · (1 − T), T = exp(−τ). τ = 0 returns C
// unchanged. With one pixel per cell the pixel's own cell has weight 1: the exact march.
// AQ_CLOUDS_CLEAR (defined by clouds.cpp for the pixels no live march cell reaches, where τ is
// exactly 0): the same result without reading τ or depth, C through the epilogue.
// aq_epilogue: the pointwise nodes after the clouds (paper relief, tint) when the host fuses
// them into this pass (AQ_NODE_EPILOGUE), else the identity.
#include "aquarelle/integer_division.glsl"

in vec2 v_uv;
out vec4 o_color;

uniform sampler2D u_image;
uniform sampler2D u_tau;  // (τ, end depth) per cell
uniform sampler2D u_depth;
uniform int u_has_depth;
uniform int u_cell;
uniform float u_max_distance;
uniform vec3 u_light_color;

void main() {
  ivec2 px = ivec2(gl_FragCoord.xy);
  vec4 c = texelFetch(u_image, px, 0);
#ifdef AQ_CLOUDS_CLEAR
  o_color = aq_epilogue(c);
  return;
#endif
  ivec2 size = textureSize(u_image, 0);
  ivec2 cells = textureSize(u_tau, 0);
  float tau = 0.0;
  if (u_cell == 1) {
    tau = texelFetch(u_tau, px, 0).r;
  } else {
    // This pixel's segment end, as the march measured it (far surfaces end at max_distance).
    float depth = u_max_distance;
    if (u_has_depth != 0) {
      ivec2 dsize = textureSize(u_depth, 0);
      float d = texelFetch(u_depth, min(aq_scaled_texel(px, size, dsize), dsize - 1), 0).r;
      if (d >= 0.0) depth = min(d, u_max_distance);
    }
    // Cell k's centre pixel is k·cell + cell/2: its position in cell units.
    vec2 f = (vec2(px) - float(u_cell / 2)) / float(u_cell);
    ivec2 base = ivec2(floor(f));
    vec2 frac = f - vec2(base);
    float sum = 0.0, weights = 0.0, nearest = 1e30, nearest_tau = 0.0;
    for (int j = 0; j < 2; ++j)
      for (int i = 0; i < 2; ++i) {
        ivec2 k = clamp(base + ivec2(i, j), ivec2(0), cells - 1);
        vec2 cell = texelFetch(u_tau, k, 0).rg;
        float bilinear = (i == 0 ? 1.0 - frac.x : frac.x) * (j == 0 ? 1.0 - frac.y : frac.y);
        float relative = abs(min(cell.g, u_max_distance) - depth) / max(depth, 1e-3);
        if (relative < nearest) {
          nearest = relative;
          nearest_tau = cell.r;
        }
        float w = bilinear * exp(-relative * relative * 400.0);  // 5 % of the depth: 1/e
        if (w > 0.0) {
          sum += w * cell.r;
          weights += w;
        }
      }
    tau = weights > 1e-4 ? sum / weights : nearest_tau;
  }
  if (!(tau > 0.0)) {
    o_color = aq_epilogue(c);
    return;
  }
  float transmittance = exp(-tau);
  o_color = aq_epilogue(vec4(c.rgb * transmittance + u_light_color * (1.0 - transmittance), c.a));
}
