// Per slot of the GPU table (layered_table.comp): the layer's Gooch-mixed light (row 0) and
// dark (row 1) colours, (mean depth, wet-in-wet, present, id) in row 2 and the Kubelka–Munk
// K and S of light (rows 3, 4) and dark (5, 6), as layer_table.cpp
// and layered_colours.frag make them for the exact method (README "Lighting colours").
layout(location = 0) out vec4 o_value;

layout(std430, binding = 0) readonly buffer Table { uint entries[]; };

uniform sampler2D u_overrides;  // per entry: row 0 (id, kind 0 palette / 1 wet, has dark)
                                // row 1 light, row 2 dark
uniform int u_override_count;
uniform bool u_wet_default;
uniform float u_light_density;
uniform float u_dark_density;
uniform float u_gooch;
uniform vec3 u_warm;
uniform vec3 u_cool;

const int kWords = 12;

vec3 pigment_mix(vec3 a, vec3 b, float t) {
#if AQ_MIX_MODE == 0
  return aq_mix_rgb(a, b, t);
#elif AQ_MIX_MODE == 1
  return aq_mix_cmyk(a, b, t);
#else
  return aq_mix_km(a, b, t);
#endif
}

float sum64(uint base) {
  return float(entries[base + 1u]) + float(entries[base]) * (1.0 / 4294967296.0);
}

void main() {
  ivec2 p = ivec2(gl_FragCoord.xy);
  uint base = uint(p.x) * uint(kWords);
  uint key = entries[base];
  uint count = entries[base + 1u];
  if (key == 0u || count == 0u) {
    o_value = vec4(0.0);
    return;
  }
  float id = uintBitsToFloat(key);
  uint depth_count = entries[base + 2u];
  float mean_depth = depth_count > 0u ? sum64(base + 3u) / float(depth_count) : 0.0;
  vec3 albedo = vec3(sum64(base + 5u), sum64(base + 7u), sum64(base + 9u)) / float(count);
  vec3 light = pow(albedo, vec3(u_light_density));
  vec3 dark = pow(albedo, vec3(u_dark_density));
  bool wet = u_wet_default;
  for (int i = 0; i < u_override_count; ++i) {
    vec4 head = texelFetch(u_overrides, ivec2(i, 0), 0);
    if (head.r != id) continue;
    if (head.g > 0.5) {
      wet = true;
      continue;
    }
    light = texelFetch(u_overrides, ivec2(i, 1), 0).rgb;
    dark = head.b > 0.5 ? texelFetch(u_overrides, ivec2(i, 2), 0).rgb
                        : pow(light, vec3(u_dark_density / u_light_density));
  }
  if (p.y == 2) {
    o_value = vec4(mean_depth, wet ? 1.0 : 0.0, 1.0, id);
    return;
  }
  vec3 c = p.y == 0 || p.y == 3 || p.y == 4 ? pigment_mix(light, u_warm, u_gooch)
                                            : pigment_mix(dark, u_cool, u_gooch);
  if (p.y < 2) {
    o_value = vec4(c, 1.0);
    return;
  }
  // Rows 3–6: the Kubelka–Munk K and S of the light (3, 4) and dark (5, 6) pigments, so the
  // composite mixes them without a logarithm per pixel.
  c = aq_pigment_sanitize(c);
  vec2 r = aq_km_ks(c.r, AQ_KM_BLACK_RATIO * c.r);
  vec2 g = aq_km_ks(c.g, AQ_KM_BLACK_RATIO * c.g);
  vec2 b = aq_km_ks(c.b, AQ_KM_BLACK_RATIO * c.b);
  o_value = p.y == 3 || p.y == 5 ? vec4(r.x, g.x, b.x, 1.0) : vec4(r.y, g.y, b.y, 1.0);
}
