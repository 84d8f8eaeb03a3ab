// The `fast` method's composite at full size (README "Fast method"): the half-resolution
// lists of blurred intensity, diffuse, depth, peak and wet edges interpolated bilinearly per
// layer (layered_lists.glsl), then the glazes of layered_composite.frag, far to near in the
// table's order (mean depth descending, then id), on the paper, and the shadow layer last.
layout(location = 0) out vec4 o_color;

uniform sampler2D u_keys;
uniform sampler2D u_blur_intensity;
uniform sampler2D u_blur_diffuse;
uniform sampler2D u_blur_depth;
uniform sampler2D u_peak;
uniform sampler2D u_blur_edges;
uniform sampler2D u_id;
uniform sampler2D u_normal;
uniform sampler2D u_depth;
#if AQ_HAS_PAPER
uniform sampler2D u_paper;
#endif
uniform sampler2D u_colours;  // per slot: Gooch light, dark, (mean depth, wet, present, id)
uniform vec2 u_size;
uniform vec3 u_half;
uniform float u_shininess;
uniform float u_specular_threshold;
uniform float u_thin;
uniform float u_line_width_scale;
uniform float u_edge_gain;
uniform float u_edge_darkness;
uniform float u_wet_spread;
uniform float u_edge_darkening;
uniform float u_depth_band;
uniform float u_granulation;
uniform float u_density;
uniform vec3 u_paper_color;
uniform float u_paper_relief;
#if AQ_HAS_SHADOW
uniform sampler2D u_shadow_layer;
uniform sampler2D u_shadow_raw;
uniform float u_shadows;
uniform vec3 u_shadow_color;
#endif

vec3 pigment_mix(vec3 a, vec3 b, float t) {
#if AQ_MIX_MODE == 0
  return aq_mix_rgb(a, b, t);
#elif AQ_MIX_MODE == 1
  return aq_mix_cmyk(a, b, t);
#else
  return aq_mix_km(a, b, t);
#endif
}

vec3 glaze(vec3 under, vec3 colour, float thickness) {
#if AQ_MIX_MODE == 2
  return aq_km_glaze(under, colour, thickness);
#else
  vec3 c = pow(aq_pigment_sanitize(colour), vec3(max(thickness, 1.0)));
  return pigment_mix(under, c, min(thickness, 1.0));
#endif
}

struct Layers {
  vec4 keys, b, bd, bz, peak, edges;
};

// The four half-resolution texels around p, the nearest first, each one's layers moved to
// the slots of the merged list.
Layers interpolate(vec2 frag) {
  ivec2 size = textureSize(u_keys, 0);
  vec2 q = frag / 2.0 - 0.5;
  vec2 f = fract(q);
  ivec2 base = ivec2(floor(q));
  ivec2 near = ivec2(step(0.5, f));  // the nearest corner
  Layers l = Layers(vec4(0.0), vec4(0.0), vec4(0.0), vec4(0.0), vec4(0.0), vec4(0.0));
  for (int n = 0; n < 4; ++n) {
    ivec2 corner = ivec2(n & 1, n >> 1) ^ near;  // n = 0 is the nearest
    vec2 w2 = mix(1.0 - f, f, vec2(corner));
    float w = w2.x * w2.y;
    ivec2 t = list_clamp(base + corner, size);
    mat4 m = list_merge(l.keys, texelFetch(u_keys, t, 0));
    l.b += w * (m * texelFetch(u_blur_intensity, t, 0));
    l.bd += w * (m * texelFetch(u_blur_diffuse, t, 0));
    l.bz += w * (m * texelFetch(u_blur_depth, t, 0));
    l.peak += w * (m * texelFetch(u_peak, t, 0));
    l.edges += w * (m * texelFetch(u_blur_edges, t, 0));
  }
  return l;
}

// One layer's glaze (layered_composite.frag's painting view).
vec3 paint(vec3 under, int slot, float b, float bd, float bz, float peak, float be, float raw,
           float t, float front, float granulation) {
  if (!(b > 1.0e-6)) return under;
  float a = layered_abstract(vec4(b), t).x;
  if (u_thin > 0.0) {
    float ridge = smoothstep(0.75, 0.9, b / max(peak, 1.0e-6));
    float wide_enough = smoothstep(0.5, 1.0, peak * u_line_width_scale);
    a = max(a, u_thin * raw * ridge * wide_enough);
  }
  float e = clamp(u_edge_gain * be, 0.0, 1.0);
  float w = 1.0 - (1.0 - e) * (1.0 - e);
  float d = clamp(bd / b, 0.0, 1.0);
  vec3 colour = pigment_mix(texelFetch(u_colours, ivec2(slot, 1), 0).rgb,
                            texelFetch(u_colours, ivec2(slot, 0), 0).rgb, d);
  bool wet_in_wet = texelFetch(u_colours, ivec2(slot, 2), 0).g > 0.5;
  float cover = a, extra = 0.0;
  if (wet_in_wet) {
    cover = max(a, u_wet_spread * w);
  } else {
    extra = u_edge_darkness * w * a;
  }
  extra += u_edge_darkening * clamp((1.0 - b) / max(1.0 - t, 1.0e-3), 0.0, 1.0) * a;
  bool has_front = front > 0.0 && front < 3.0e38;
  float visible =
      has_front ? 1.0 - smoothstep(0.0, max(u_depth_band, 1.0e-6), bz / b - front) : 1.0;
  return glaze(under, colour, u_density * cover * visible * granulation * (1.0 + extra));
}

void main() {
  ivec2 p = ivec2(gl_FragCoord.xy);
#if AQ_HAS_PAPER
  float h = texture(u_paper, gl_FragCoord.xy / u_size).r;
  h = h >= 0.0 ? min(h, 1.0) : 0.5;
#else
  float h = 0.5;
#endif
  vec3 under = u_paper_color * (1.0 + u_paper_relief * (h - 0.5));
  float granulation = mix(1.0, 2.0 * (1.0 - h), u_granulation);
  Layers l = interpolate(gl_FragCoord.xy);
  float id = texelFetch(u_id, p, 0).r;
  vec3 n = texelFetch(u_normal, p, 0).xyz;
  float len = length(n);
  n = len > 1.0e-6 && len < 1.0e30 ? n / len : vec3(0.0);
  float lit_part = pow(max(dot(n, u_half), 0.0), u_shininess) >= u_specular_threshold ? 0.0 : 1.0;
  float front = texelFetch(u_depth, p, 0).r;
  float t = layered_threshold(gl_FragCoord.xy);
  // Far to near: mean depth descending, then id ascending (insertion sort of four).
  int order[4] = int[4](0, 1, 2, 3);
  vec4 depth_of = vec4(0.0), id_of = vec4(0.0);
  for (int k = 0; k < 4; ++k) {
    if (!(l.keys[k] > 0.5)) continue;
    vec4 row = texelFetch(u_colours, ivec2(int(l.keys[k]) - 1, 2), 0);
    depth_of[k] = row.r;
    id_of[k] = row.a;
  }
  for (int i = 1; i < 4; ++i) {
    for (int j = i; j > 0; --j) {
      int a = order[j - 1], c = order[j];
      bool swap = depth_of[c] > depth_of[a] || (depth_of[c] == depth_of[a] && id_of[c] < id_of[a]);
      if (!swap) break;
      order[j - 1] = c;
      order[j] = a;
    }
  }
  for (int i = 0; i < 4; ++i) {
    int k = order[i];
    if (!(l.keys[k] > 0.5)) continue;
    float raw = id == id_of[k] ? lit_part : 0.0;
    under = paint(under, int(l.keys[k]) - 1, l.b[k], l.bd[k], l.bz[k], l.peak[k], l.edges[k], raw,
                  t, front, granulation);
  }
#if AQ_HAS_SHADOW
  if (texelFetch(u_shadow_raw, p, 0).g > 0.5) {
    vec2 s = texelFetch(u_shadow_layer, p, 0).rg;
    float shadow = s.y > 1.0e-6 ? clamp(s.x / s.y, 0.0, 1.0) : 0.0;
    under = glaze(under, u_shadow_color, u_shadows * shadow);
  }
#endif
  o_color = vec4(under, 1.0);
}
