// Glazes the four layers of a range, far to near, over what lies under them (README.md):
//   a     = smoothstep(t − s, t + s, blurred intensity)              abstraction
//   d     = blurred diffuse / blurred intensity                        normalised lighting
//   C     = mix_pigment(dark, light, d)                                colour of the wash
//   w     = ease_out(gain · blurred edges)                             wet edge weight
//   wet-to-dry: cover = a,                 extra = edge_darkness · w · a   (darker rim)
//   wet-in-wet: cover = max(a, spread · w), extra = 0                  (feathers outwards)
//   extra += edge_darkening · clamp((1 − b) / (1 − t), 0, 1) · a       (inverted blur)
//   v     = 1 − smoothstep(0, depth_band, z_layer − z_front)           blurred depth test
//   g     = mix(1, 2 (1 − paper), granulation)                         granulation
//   thickness = density · cover · v · g · (1 + extra);  under = glaze(under, C, thickness)
// and, after the last range's layers, the soft shadow as its own translucent layer:
//   S = (G_σs * shadow) / (G_σs * receivers);  under = glaze(under, shadow_color, shadows · S · R)
layout(location = 0) out vec4 o_color;

uniform sampler2D u_under;
uniform sampler2D u_intensity;  // raw (views)
uniform sampler2D u_diffuse;    // raw (views)
uniform sampler2D u_blur_intensity;
uniform sampler2D u_blur_diffuse;
uniform sampler2D u_blur_depth;
uniform sampler2D u_blur_edges;
uniform sampler2D u_depth;
#if AQ_HAS_PAPER
uniform sampler2D u_paper;
#endif
uniform vec2 u_size;
uniform sampler2D u_peak;  // peak of the blurred intensity over a window of radius ~σa
uniform float u_thin;      // thin_shapes: how much of a thin shape the abstraction keeps
uniform float u_line_width_scale;  // √(2π) σa: a thin line's blurred peak times it = its width
uniform sampler2D u_owner;  // per channel: 1 + the layer painting here, 0 for none
uniform sampler2D u_table;  // per layer: row 0 (id, wet-in-wet, range), row 1 light, row 2 dark
uniform float u_range;      // this range: owner entries of other ranges are stale
uniform float u_edge_gain;
uniform float u_edge_darkness;
uniform float u_wet_spread;
uniform float u_edge_darkening;
uniform float u_depth_band;
uniform float u_granulation;
uniform float u_density;
uniform sampler2D u_colours;  // per layer: Gooch light (row 0) and dark (row 1), see layered_colours
#if AQ_HAS_SHADOW
uniform sampler2D u_shadow_layer;  // blurred (shadow, receivers), see layered_shadow.frag
uniform sampler2D u_shadow_raw;    // unblurred: g = 1 on receivers
uniform bool u_last;               // the last range glazes the shadow layer over everything
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
  // Beyond unit thickness the wash darkens as a filter would (Beer–Lambert), then it covers.
  vec3 c = pow(aq_pigment_sanitize(colour), vec3(max(thickness, 1.0)));
  return pigment_mix(under, c, min(thickness, 1.0));
#endif
}

// The range's layers glazed over `under` at p, far to near.
vec3 paint_layers(ivec2 p, vec4 owner, vec3 under) {
  vec4 b = texelFetch(u_blur_intensity, p, 0);
  vec4 bd = texelFetch(u_blur_diffuse, p, 0);
  vec4 bz = texelFetch(u_blur_depth, p, 0);
  vec4 be = texelFetch(u_blur_edges, p, 0);
  vec4 raw = texelFetch(u_intensity, p, 0);
  vec4 raw_diffuse = texelFetch(u_diffuse, p, 0);
  float t = layered_threshold(gl_FragCoord.xy);
  vec4 a = layered_abstract(b, t);
  if (u_thin > 0.0) {
    // Thin shapes (README): a pixel of the object that is the peak of its blurred mask (the
    // ridge of a blade, not the rounded-off corner of a wide shape) and at least about half a
    // pixel wide keeps its coverage.
    vec4 peak = texelFetch(u_peak, p, 0);
    vec4 ridge = smoothstep(vec4(0.75), vec4(0.9), b / max(peak, vec4(1.0e-6)));
    vec4 wide_enough = smoothstep(vec4(0.5), vec4(1.0), peak * u_line_width_scale);
    a = max(a, u_thin * raw * ridge * wide_enough);
  }
  vec4 w = layered_ease_out(u_edge_gain * be);
  float front = texelFetch(u_depth, p, 0).r;
  bool has_front = front > 0.0 && front < 3.0e38;
#if AQ_HAS_PAPER
  float h = texture(u_paper, gl_FragCoord.xy / u_size).r;
  h = h >= 0.0 ? min(h, 1.0) : 0.5;
#else
  float h = 0.5;
#endif
  float granulation = mix(1.0, 2.0 * (1.0 - h), u_granulation);
  for (int k = 0; k < 4; ++k) {
    if (!(owner[k] > 0.5)) continue;
    int layer = int(owner[k]) - 1;
    if (texelFetch(u_table, ivec2(layer, 0), 0).b != u_range) continue;
    vec3 light_color = texelFetch(u_table, ivec2(layer, 1), 0).rgb;
    vec3 dark_color = texelFetch(u_table, ivec2(layer, 2), 0).rgb;
    bool wet_in_wet = texelFetch(u_table, ivec2(layer, 0), 0).g > 0.5;
#if AQ_VIEW == 1  // segments: flat light colour on the raw masks
    under = glaze(under, light_color, raw[k]);
#elif AQ_VIEW == 2  // lighting: the raw lit layers, highlights left white
    float rd = raw[k] > 0.0 ? raw_diffuse[k] / raw[k] : 0.0;
    under = glaze(under, pigment_mix(dark_color, light_color, rd), raw[k]);
#else
    if (!(b[k] > 1.0e-6)) continue;
    float d = clamp(bd[k] / b[k], 0.0, 1.0);
    vec3 light = texelFetch(u_colours, ivec2(layer, 0), 0).rgb;  // Gooch-mixed, per layer
    vec3 dark = texelFetch(u_colours, ivec2(layer, 1), 0).rgb;
    vec3 colour = pigment_mix(dark, light, d);
#if AQ_VIEW == 3  // abstraction only
    under = glaze(under, colour, a[k]);
#elif AQ_VIEW == 4  // wet edge weights, grey
    under = glaze(under, vec3(0.35), w[k]);
#else
    float cover = a[k];
    float extra = 0.0;
    if (wet_in_wet) {
      cover = max(a[k], u_wet_spread * w[k]);
    } else {
      extra = u_edge_darkness * w[k] * a[k];
    }
    extra += u_edge_darkening * clamp((1.0 - b[k]) / max(1.0 - t, 1.0e-3), 0.0, 1.0) * a[k];
    float z = bz[k] / b[k];
    float visible = has_front ? 1.0 - smoothstep(0.0, max(u_depth_band, 1.0e-6), z - front) : 1.0;
    float thickness = u_density * cover * visible * granulation * (1.0 + extra);
    under = glaze(under, colour, thickness);
#endif
#endif
  }
  return under;
}

void main() {
  ivec2 p = ivec2(gl_FragCoord.xy);
  vec3 under = texelFetch(u_under, p, 0).rgb;
  vec4 owner = texelFetch(u_owner, p, 0);
  // Pixels where no layer of the range paints keep what lies under them.
  if (any(greaterThan(owner, vec4(0.5)))) under = paint_layers(p, owner, under);
#if AQ_HAS_SHADOW && AQ_VIEW == 0
  if (u_last && texelFetch(u_shadow_raw, p, 0).g > 0.5) {
    vec2 s = texelFetch(u_shadow_layer, p, 0).rg;
    float shadow = s.y > 1.0e-6 ? clamp(s.x / s.y, 0.0, 1.0) : 0.0;
    under = glaze(under, u_shadow_color, u_shadows * shadow);
  }
#endif
  o_color = vec4(under, 1.0);
}
