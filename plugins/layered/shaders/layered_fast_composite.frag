// The `fast` method's composite at full size (README "Fast method"): per pixel its cell's
// merged list of layers, already far to near in the table's order (mean depth descending,
// then id; layered_fast_cells.frag), each layer's blurred intensity, diffuse, depth, wet edge
// and peak interpolated bilinearly by the texture unit inside the cell's block
// (layered_fast_blocks.frag), then the glazes of layered_composite.frag on the paper, and the
// shadow layer last.
layout(location = 0) out vec4 o_color;

#ifndef AQ_LAYER_COUNT
#define AQ_LAYER_COUNT 4  // every slot (a draw without the classes)
#endif

uniform sampler2D u_threshold_map;  // (layered_threshold, paper height) per pixel, kept
uniform sampler2D u_cells;  // per cell its merged keys, far to near (layered_fast_cells.frag)
uniform sampler2D u_slot0;  // per cell a 2 x 2 block per slot (layered_fast_blocks.frag)
uniform sampler2D u_slot1;
uniform sampler2D u_slot2;
uniform sampler2D u_slot3;
uniform sampler2D u_block_peak;  // the four slots' peaks, in the same blocks
uniform sampler2D u_pixels;  // per pixel (id, 1 − highlight, depth, 0): layered_fast_segment.frag
uniform sampler2D u_colours;  // per slot, 4 rows: layered_fast_colours.frag
uniform vec2 u_size;
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

// One listed layer's glaze: its pigments and id from the table (rows 0 and 1), its values
// from the cell's block, interpolated by the texture unit (v: blurred I, D, Z and wet edge).
vec3 layer(vec3 under, float key, vec4 v, float peak, float id, float lit_part, float t,
           float front, float granulation) {
  int slot = int(key) - 1;
  vec4 row0 = texelFetch(u_colours, ivec2(slot, 0), 0);
  vec4 row1 = texelFetch(u_colours, ivec2(slot, 1), 0);
  float raw = id == abs(row1.a) ? lit_part : 0.0;
  return paint(under, slot, row1.a < 0.0, v.x, v.y, v.z, peak, v.w, raw, t, front, granulation,
               row0.rgb, row1.rgb);
}

void main() {
  ivec2 p = ivec2(gl_FragCoord.xy);
  // layered_threshold and the paper's height, kept between frames (layered_fast_threshold.frag)
  vec2 kept = texelFetch(u_threshold_map, p, 0).rg;
  float t = kept.x, h = kept.y;
  vec3 under = u_paper_color * (1.0 + u_paper_relief * (h - 0.5));
  float granulation = mix(1.0, 2.0 * (1.0 - h), u_granulation);
  // The cell around this pixel (between the texels at base and base + 1) and the position in
  // its 2 x 2 block that interpolates the four corners bilinearly.
  vec2 q = gl_FragCoord.xy / float(AQ_DIVISOR) - 0.5;
  vec2 base = floor(q);
  ivec2 cell = ivec2(base) + 1;
  vec4 keys = texelFetch(u_cells, cell, 0);  // far to near, empty slots last
  vec2 uv = (2.0 * vec2(cell) + 0.5 + (q - base)) / vec2(textureSize(u_slot0, 0));
  vec4 peak = texture(u_block_peak, uv);
  vec4 pixel = texelFetch(u_pixels, p, 0);  // the segmentation's (id, 1 − highlight, depth)
  float id = pixel.x, lit_part = pixel.y, front = pixel.z;
  // The cell's layers in order, up to the last listed one of this draw's pixels (AQ_LAYER_COUNT:
  // layered_fast_classes.frag sorted the pixels into classes by it, and the depth test lets
  // only this class in). llvmpipe runs every call below for every pixel of a group, listed or
  // not (neither a branch nor a loop is skipped, measured), so the classes are what keep a
  // pixel with one layer from paying for four.
#if AQ_LAYER_COUNT > 0
  if (keys.x > 0.5)
    under = layer(under, keys.x, texture(u_slot0, uv), peak.x, id, lit_part, t, front, granulation);
#endif
#if AQ_LAYER_COUNT > 1
  if (keys.y > 0.5)
    under = layer(under, keys.y, texture(u_slot1, uv), peak.y, id, lit_part, t, front, granulation);
#endif
#if AQ_LAYER_COUNT > 2
  if (keys.z > 0.5)
    under = layer(under, keys.z, texture(u_slot2, uv), peak.z, id, lit_part, t, front, granulation);
#endif
#if AQ_LAYER_COUNT > 3
  if (keys.w > 0.5)
    under = layer(under, keys.w, texture(u_slot3, uv), peak.w, id, lit_part, t, front, granulation);
#endif
#if AQ_HAS_SHADOW
  // The shadow layer's sums at the lists' resolution, enlarged bilinearly, on receivers.
  vec2 s = texture(u_shadow_layer, gl_FragCoord.xy / (float(AQ_DIVISOR) * vec2(textureSize(u_shadow_layer, 0)))).rg;
  float shadow = id >= 1.0 && s.y > 1.0e-6 ? clamp(s.x / s.y, 0.0, 1.0) : 0.0;
  under = aq_pigment_sanitize(km_over(u_shadow_k, u_shadow_s, u_shadows * shadow, under));
#endif
  o_color = vec4(under, 1.0);
}
