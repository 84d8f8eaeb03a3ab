// Watercolor reflectance (plugins/dilution/README.md), after Montesdeoca et al.:
//   D = N·L,  lit = clamp((D + a − 1) / a, 0, 1)              a = diffuse_area
//   C_c = albedo + clamp(cangiante · lit, 0, 1)                (cangiante: lighter in the light)
//   τ = turbulence · fbm3(object position · scale)   (bend > 0: fbm3_bent, seed 002's cubism)
//   dil = clamp(dilution · lit · (1 + τ), 0, 1)
//   out = mix(C_c, paper, dil) · (1 − shade · (1 − lit))
// The background (albedo alpha 0) passes unchanged with dil = 0. Alpha is 1: the painting is opaque.
#include "aquarelle/noise.glsl"

in vec2 v_uv;
layout(location = 0) out vec4 o_color;
layout(location = 1) out vec4 o_dilution;

uniform sampler2D u_albedo;
uniform sampler2D u_normal;
uniform sampler2D u_anchor;  // object-space (or world) position
uniform vec3 u_to_light;
uniform vec3 u_paper;
uniform float u_dilution;
uniform float u_area;
uniform float u_cangiante;
uniform float u_shade;
uniform float u_turbulence;
uniform float u_scale;
uniform int u_octaves;
uniform float u_bend;  // > 0: seed 002's cubism, the turbulence blended by a bent smoothstep

void main() {
  ivec2 p = ivec2(gl_FragCoord.xy);
  vec4 albedo = texelFetch(u_albedo, p, 0);
  if (!(albedo.a > 0.0)) {
    o_color = vec4(albedo.rgb, 1.0);  // the painting is opaque: the environment is painted too
    o_dilution = vec4(0.0);
    return;
  }
  vec3 n = texelFetch(u_normal, p, 0).xyz;
  float d = dot(n, u_to_light);
  float lit = clamp((d + u_area - 1.0) / u_area, 0.0, 1.0);
  if (isnan(lit)) lit = 0.0;
  float turbulence = 0.0;
  if (u_turbulence > 0.0) {
    vec3 anchor = texelFetch(u_anchor, p, 0).xyz;
    turbulence = u_turbulence * (u_bend > 0.0 ? aq_fbm3_bent(anchor * u_scale, u_octaves, u_bend)
                                              : aq_fbm3(anchor * u_scale, u_octaves));
    if (isnan(turbulence) || isinf(turbulence)) turbulence = 0.0;
  }
  float dil = clamp(u_dilution * lit * (1.0 + turbulence), 0.0, 1.0);
  vec3 cangiante = albedo.rgb + clamp(u_cangiante * lit, 0.0, 1.0);
  vec3 c = mix(cangiante, u_paper, dil) * (1.0 - u_shade * (1.0 - lit));
  o_color = vec4(c, 1.0);
  o_dilution = vec4(dil, dil, dil, 1.0);
}
