// The `fast` method's composite at full size (README "Fast method"): the half-resolution
// lists of blurred intensity, diffuse, depth, peak and wet edges interpolated bilinearly per
// layer (layered_lists.glsl), then the glazes of layered_composite.frag, far to near in the
// table's order (mean depth descending, then id), on the paper, and the shadow layer last.
layout(location = 0) out vec4 o_color;

uniform sampler2D u_keys;
uniform sampler2D u_threshold_map;  // layered_threshold per pixel (layered_fast_threshold.frag)
uniform sampler2D u_cells;  // a texel's list where it and its +x, +y, +xy neighbours agree, else -1
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
uniform sampler2D u_colours;  // per slot, 4 rows: layered_fast_colours.frag
uniform vec2 u_size;
uniform vec3 u_half;
uniform float u_shininess;
uniform float u_specular_threshold;
uniform float u_thin;
uniform vec2 u_ridge;  // the ridge test's smooth step on b / m (README "Fast method")
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
uniform float u_shadows;
uniform vec3 u_shadow_k;  // the shadow colour's Kubelka–Munk K and S
uniform vec3 u_shadow_s;
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

// Kubelka–Munk layer of thickness x and constants (k, s) over a background reflecting r2
// (aq_km_layer and aq_km_over, with sinh and cosh from one exp: llvmpipe evaluates each of
// them with two).
vec3 km_over(vec3 k, vec3 s, float x, vec3 r2) {
  vec3 q = k / max(s, vec3(1.0e-30));
  vec3 a = 1.0 + q;
  vec3 b = sqrt(max(q * (q + 2.0), vec3(1.0e-12)));
  vec3 e = exp(min(b * s * x, vec3(40.0)));
  vec3 ie = 1.0 / e;
  vec3 sh = 0.5 * (e - ie), ch = 0.5 * (e + ie);
  vec3 c = a * sh + b * ch;
  vec3 r = sh / c, tr = b / c;
  vec3 over = r + tr * tr * r2 / (1.0 - r * r2);
  return mix(r2, over, vec3(greaterThan(s, vec3(0.0))));  // no scattering: no layer
}

vec3 glaze(vec3 under, vec3 colour, float thickness) {
#if AQ_MIX_MODE == 2
  if (!(thickness > 0.0)) return aq_pigment_sanitize(under);
  colour = aq_pigment_sanitize(colour);
  vec2 kr = aq_km_ks(colour.r, AQ_KM_BLACK_RATIO * colour.r);
  vec2 kg = aq_km_ks(colour.g, AQ_KM_BLACK_RATIO * colour.g);
  vec2 kb = aq_km_ks(colour.b, AQ_KM_BLACK_RATIO * colour.b);
  return aq_pigment_sanitize(
      km_over(vec3(kr.x, kg.x, kb.x), vec3(kr.y, kg.y, kb.y), thickness, aq_pigment_sanitize(under)));
#else
  vec3 c = pow(aq_pigment_sanitize(colour), vec3(max(thickness, 1.0)));
  return pigment_mix(under, c, min(thickness, 1.0));
#endif
}

struct Layers {
  vec4 keys, b, bd, bz, peak, edges;
};

// The four low-resolution texels around p, bilinearly. Where they hold the same list
// (u_cells, layered_fast_cells.frag: most of the image) the texture unit's bilinear filter
// does it, one fetch per layer of the list; elsewhere each corner's layers are moved to the
// slots of a merged list, the nearest corner first. Both are loops whose condition is per
// pixel: llvmpipe runs both sides of a branch under a mask, but leaves a loop as soon as no
// pixel of the group needs another turn.
Layers interpolate(vec2 frag) {
  ivec2 size = textureSize(u_keys, 0);
  vec2 q = frag / float(AQ_DIVISOR) - 0.5;
  ivec2 base = ivec2(floor(q));
  vec4 cell = texelFetch(u_cells, clamp(base, ivec2(0), size - 1), 0);
  vec2 strip = vec2(textureSize(u_cells, 0));
  vec2 uv = (q + 0.5) / strip;
  vec2 part = vec2(float(size.x) / strip.x, 0.0);
  vec2 st = (q + 0.5) / vec2(size);
  Layers l = Layers(cell, vec4(0.0), vec4(0.0), vec4(0.0), texture(u_peak, st), vec4(0.0));
  for (int k = 0; k < 4 && cell[k] > 0.5; ++k) {
    vec4 v = texture(u_cells, uv + float(k + 1) * part);
    l.b[k] = v.x;
    l.bd[k] = v.y;
    l.bz[k] = v.z;
    l.edges[k] = v.w;
  }
  bool merge = cell.x < 0.0 || any(lessThan(base, ivec2(0))) || any(greaterThanEqual(base + 1, size));
  vec2 f = fract(q);
  ivec2 near = ivec2(step(0.5, f));  // the nearest corner
  for (int n = 0; merge && n < 4; ++n) {
    if (n == 0) l = Layers(vec4(0.0), vec4(0.0), vec4(0.0), vec4(0.0), vec4(0.0), vec4(0.0));
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

// The wash: d mixes the layer's dark and light pigments, glazed `thickness` thick over
// `under`; c0 and c1 are the rgb of the layer's rows 0 and 1 (the light and dark colours, or
// with Kubelka–Munk the light pigment's K and S). Kubelka–Munk: the K and S of both pigments
// come from the colours pass and are mixed by concentration, and the mixture itself is laid
// (the exact method lays the pigment whose unit layer looks like the mixture, which is the same
// pigment at d = 0 and 1 and close to it between; README "Fast method").
vec3 wash(vec3 under, int slot, float d, float thickness, vec3 c0, vec3 c1) {
#if AQ_MIX_MODE == 2
  vec3 k = mix(texelFetch(u_colours, ivec2(slot, 2), 0).rgb, c0, d);
  vec3 s = mix(texelFetch(u_colours, ivec2(slot, 3), 0).rgb, c1, d);
  return aq_pigment_sanitize(km_over(k, s, thickness, aq_pigment_sanitize(under)));
#else
  return glaze(under, pigment_mix(c1, c0, d), thickness);
#endif
}

// One layer's glaze (layered_composite.frag's painting view); a layer that puts down no
// pigment here (thickness under 1e-5) costs no colour mixing.
vec3 paint(vec3 under, int slot, bool wet_in_wet, float b, float bd, float bz, float peak,
           float be, float raw, float t, float front, float granulation, vec3 c0, vec3 c1) {
  if (!(b > 1.0e-6)) return under;
  float a = layered_abstract(vec4(b), t).x;
  if (u_thin > 0.0) {
    float ridge = smoothstep(u_ridge.x, u_ridge.y, b / max(peak, 1.0e-6));
    float wide_enough = smoothstep(0.5, 1.0, peak * u_line_width_scale);
    a = max(a, u_thin * raw * ridge * wide_enough);
  }
  float e = clamp(u_edge_gain * be, 0.0, 1.0);
  float w = 1.0 - (1.0 - e) * (1.0 - e);
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
  float thickness = u_density * cover * visible * granulation * (1.0 + extra);
  if (!(thickness > 1.0e-5)) return under;
  return wash(under, slot, clamp(bd / b, 0.0, 1.0), thickness, c0, c1);
}

// A pixel's layers with their table rows: mean depth, id, wet-in-wet and the rgb of rows 0 and
// 1 per channel (vec4s over the layers: a local array indexed by the loop is slow on llvmpipe).
struct Ordered {
  Layers l;
  vec4 depth, id, wet, r0, g0, b0, r1, g1, b1;
};

void swap_component(inout vec4 v, int a, int c) {
  float x = v[a];
  v[a] = v[c];
  v[c] = x;
}

// Puts layers a < c (constant components) far to near: c first if it lies farther, or as far
// with a smaller id; empty slots (depth −3e38) stay behind.
void order_pair(inout Ordered o, int a, int c) {
  bool swap = o.depth[c] > o.depth[a] || (o.depth[c] == o.depth[a] && o.id[c] < o.id[a]);
  if (!swap) return;
  swap_component(o.l.keys, a, c);
  swap_component(o.l.b, a, c);
  swap_component(o.l.bd, a, c);
  swap_component(o.l.bz, a, c);
  swap_component(o.l.peak, a, c);
  swap_component(o.l.edges, a, c);
  swap_component(o.depth, a, c);
  swap_component(o.id, a, c);
  swap_component(o.wet, a, c);
  swap_component(o.r0, a, c);
  swap_component(o.g0, a, c);
  swap_component(o.b0, a, c);
  swap_component(o.r1, a, c);
  swap_component(o.g1, a, c);
  swap_component(o.b1, a, c);
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
  float t = texelFetch(u_threshold_map, p, 0).r;  // layered_threshold, kept between frames
  // Far to near: mean depth descending, then id ascending, empty slots last. A sorting network
  // with fixed components (indexing a local array by a computed index is slow on llvmpipe);
  // then the layers in order. llvmpipe runs both sides of a branch under a mask but leaves a
  // loop once no pixel of the group needs another turn, so the loop costs what the group's
  // longest list needs: one layer in most of the image.
  Ordered o = Ordered(l, vec4(-3.0e38), vec4(0.0), vec4(0.0), vec4(0.0), vec4(0.0), vec4(0.0),
                      vec4(0.0), vec4(0.0), vec4(0.0));
  for (int k = 0; k < 4 && l.keys[k] > 0.5; ++k) {
    vec4 row0 = texelFetch(u_colours, ivec2(int(l.keys[k]) - 1, 0), 0);
    vec4 row1 = texelFetch(u_colours, ivec2(int(l.keys[k]) - 1, 1), 0);
    o.depth[k] = row0.a;
    o.id[k] = abs(row1.a);
    o.wet[k] = row1.a < 0.0 ? 1.0 : 0.0;
    o.r0[k] = row0.r;
    o.g0[k] = row0.g;
    o.b0[k] = row0.b;
    o.r1[k] = row1.r;
    o.g1[k] = row1.g;
    o.b1[k] = row1.b;
  }
  order_pair(o, 0, 1);
  order_pair(o, 2, 3);
  order_pair(o, 0, 2);
  order_pair(o, 1, 3);
  order_pair(o, 1, 2);
  for (int i = 0; i < 4 && o.l.keys[i] > 0.5; ++i) {
    float raw = id == o.id[i] ? lit_part : 0.0;
    under = paint(under, int(o.l.keys[i]) - 1, o.wet[i] > 0.5, o.l.b[i], o.l.bd[i], o.l.bz[i],
                  o.l.peak[i], o.l.edges[i], raw, t, front, granulation,
                  vec3(o.r0[i], o.g0[i], o.b0[i]), vec3(o.r1[i], o.g1[i], o.b1[i]));
  }
#if AQ_HAS_SHADOW
  // The shadow layer's sums at the lists' resolution, enlarged bilinearly, on receivers.
  vec2 s = texture(u_shadow_layer, gl_FragCoord.xy / (float(AQ_DIVISOR) * vec2(textureSize(u_shadow_layer, 0)))).rg;
  float shadow = id >= 1.0 && s.y > 1.0e-6 ? clamp(s.x / s.y, 0.0, 1.0) : 0.0;
  under = aq_pigment_sanitize(km_over(u_shadow_k, u_shadow_s, u_shadows * shadow, under));
#endif
  o_color = vec4(under, 1.0);
}
