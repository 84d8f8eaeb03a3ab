// Per slot of the GPU table (layered_table.comp), four rows: row 0 (light.rgb, mean depth),
// row 1 (dark.rgb, id; −id for wet-in-wet), where light and dark are the Gooch-mixed colours as
// layer_table.cpp and layered_colours.frag make them for the exact method (README "Lighting
// colours"); with Kubelka–Munk mixing rows 0–3 hold the pigments' K and S instead: K light,
// S light, K dark, S dark (the depth and id in rows 0 and 1 as before).
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
  // Row 0 carries the mean depth and row 1 the id (negative: wet-in-wet): the composite orders
  // its layers from the two rows it reads for their pigments anyway.
  float order = p.y == 0 ? mean_depth : p.y == 1 ? (wet ? -id : id) : 0.0;
  vec3 c = p.y == 0 || (AQ_MIX_MODE == 2 && p.y == 1) ? pigment_mix(light, u_warm, u_gooch)
                                                      : pigment_mix(dark, u_cool, u_gooch);
#if AQ_MIX_MODE == 2
  // The Kubelka–Munk K (rows 0, 2) and S (1, 3) of the light and dark pigments, so the
  // composite mixes them without a logarithm per pixel.
  c = aq_pigment_sanitize(c);
  vec2 r = aq_km_ks(c.r, AQ_KM_BLACK_RATIO * c.r);
  vec2 g = aq_km_ks(c.g, AQ_KM_BLACK_RATIO * c.g);
  vec2 b = aq_km_ks(c.b, AQ_KM_BLACK_RATIO * c.b);
  c = p.y == 0 || p.y == 2 ? vec3(r.x, g.x, b.x) : vec3(r.y, g.y, b.y);
#endif
  o_value = vec4(c, order);
}
