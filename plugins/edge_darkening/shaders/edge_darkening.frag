// Edge darkening from the blur difference (plugins/edge_darkening/README.md):
//   d = max_rgb |blur(S) − S|,  k = strength · (control.g + grazing · control.b)  (or strength)
//   e = e_max · (1 − exp(−k·d / e_max))   (slope k·d where it is small, never past e_max)
//   out_c = C_c · min(C_c, 1)^e   (= C_c^(1 + e) for C_c in [0, 1]; values > 1 and <= 0 kept)
// The grazing angle is read through a 3×3 tent (four bilinear reads): a box's side face seen
// edge-on is a one-pixel strip of grazing 1, which unfiltered drew aliased black lines along
// thin geometry and blots at corners.
// d at or under the dead zone (the rounding of a blurred constant) and non-finite d are 0, so a
// flat area is returned bit-exact and a NaN neighbour never spreads.
#include "aquarelle/integer_division.glsl"

in vec2 v_uv;
out vec4 o_color;

uniform sampler2D u_image;
uniform sampler2D u_source;
uniform sampler2D u_blurred;  // blur(source), at the source's size or on 2×2 cells (bilinear)
uniform sampler2D u_control;
uniform int u_has_control;
uniform float u_strength;
uniform float u_grazing;
uniform float u_dead_zone;
uniform float u_max_exponent;

void main() {
  ivec2 p = ivec2(gl_FragCoord.xy);
  vec4 c = texelFetch(u_image, p, 0);
  ivec2 ps = min(aq_scaled_texel(p, textureSize(u_image, 0), textureSize(u_source, 0)),
                 textureSize(u_source, 0) - 1);
  vec3 s = texelFetch(u_source, ps, 0).rgb;
  vec3 b = texture(u_blurred, (vec2(ps) + 0.5) / vec2(textureSize(u_source, 0))).rgb;
  vec3 diff = abs(b - s);
  float d = max(diff.r, max(diff.g, diff.b));
  float scale = max(1.0, max(abs(s.r), max(abs(s.g), abs(s.b))));
  if (!(d > u_dead_zone * scale) || isinf(d)) d = 0.0;  // also NaN
  float k = u_strength;
  if (u_has_control != 0) {
    ivec2 pc = min(aq_scaled_texel(p, textureSize(u_image, 0), textureSize(u_control, 0)),
                   textureSize(u_control, 0) - 1);
    vec4 control = texelFetch(u_control, pc, 0);
    vec2 centre = (vec2(pc) + 0.5) / vec2(textureSize(u_control, 0));
    vec2 half_texel = 0.5 / vec2(textureSize(u_control, 0));
    float grazing = 0.25 * (texture(u_control, centre + half_texel * vec2(-1.0, -1.0)).b +
                            texture(u_control, centre + half_texel * vec2(1.0, -1.0)).b +
                            texture(u_control, centre + half_texel * vec2(-1.0, 1.0)).b +
                            texture(u_control, centre + half_texel * vec2(1.0, 1.0)).b);
    k *= max(control.g + u_grazing * grazing, 0.0);
    if (isnan(k) || isinf(k)) k = 0.0;
  }
  float e = k * d;
  if (u_max_exponent > 0.0) e = u_max_exponent * (1.0 - exp(-e / u_max_exponent));
  if (!(e > 0.0)) {
    o_color = c;
    return;
  }
  vec3 darker = c.rgb;
  for (int i = 0; i < 3; ++i) {
    if (c[i] > 0.0 && c[i] < 1.0) darker[i] = c[i] * pow(c[i], e);
  }
  o_color = vec4(darker, c.a);
}
