// The per-layer Gooch colours, once per frame instead of once per pixel (they are constant over
// a layer): row 0 light mixed towards warm, row 1 dark mixed towards cool, in the chosen
// mixing (README: "Lighting colours"). One texel per layer of the table.
layout(location = 0) out vec4 o_colour;

uniform sampler2D u_table;  // per layer: row 0 (id, wet-in-wet), row 1 light, row 2 dark
uniform float u_gooch;
uniform vec3 u_warm;
uniform vec3 u_cool;

vec3 pigment_mix(vec3 a, vec3 b, float t) {
#if AQ_MIX_MODE == 0
  return aq_mix_rgb(a, b, t);
#elif AQ_MIX_MODE == 1
  return aq_mix_cmyk(a, b, t);
#else
  return aq_mix_km(a, b, t);
#endif
}

void main() {
  ivec2 p = ivec2(gl_FragCoord.xy);
  vec3 light = texelFetch(u_table, ivec2(p.x, 1), 0).rgb;
  vec3 dark = texelFetch(u_table, ivec2(p.x, 2), 0).rgb;
  o_colour = vec4(p.y == 0 ? pigment_mix(light, u_warm, u_gooch)
                           : pigment_mix(dark, u_cool, u_gooch), 1.0);
}
