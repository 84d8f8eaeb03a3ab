// Per slot of the GPU table (layered_table.comp): the layer's Gooch-mixed light (row 0) and
// dark (row 1) colours and (mean depth, wet-in-wet, present, id) in row 2, as layer_table.cpp
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
  if (p.y == 0) {
    o_value = vec4(pigment_mix(light, u_warm, u_gooch), 1.0);
  } else if (p.y == 1) {
    o_value = vec4(pigment_mix(dark, u_cool, u_gooch), 1.0);
  } else {
    o_value = vec4(mean_depth, wet ? 1.0 : 0.0, 1.0, id);
  }
}
