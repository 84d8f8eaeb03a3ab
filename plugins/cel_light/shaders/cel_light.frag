// Deferred light and cel shading (Paré-Vogt & Chaid §2.3 "Light" pass and §3.1):
//   lit  = albedo * (ambient + light * max(N.L, 0) * visibility * caustic)
//   v    = max(r, g, b)                         (HSV value)
//   v'   = floor(v * (levels - 1) + 0.5) / (levels - 1)    (levels >= 2; levels = 1: v' = 1)
//   out  = lit * v' / v                         (hue and saturation kept exactly)
// Scaling rgb by v'/v is the HSV round trip with a new value, without the hue arithmetic, so
// grey, black and values above 1 need no special case. Output stays linear HDR.
in vec2 v_uv;
layout(location = 0) out vec4 o_color;

uniform sampler2D u_position;
uniform sampler2D u_normal;
uniform sampler2D u_albedo;
uniform sampler2D u_id;
uniform sampler2D u_shadow;
uniform sampler2D u_caustics;
uniform bool u_has_shadow;
uniform bool u_has_caustics;

uniform mat4 u_light_view_projection;
uniform vec3 u_light_direction;  // direction light travels, unit
uniform vec3 u_light_color;
uniform vec3 u_ambient;
uniform int u_pcf_radius;

uniform float u_water_height;
uniform float u_caustic_tile;  // world units per caustic texture period
uniform float u_caustic_strength;

uniform bool u_quantize;
uniform int u_levels;
uniform vec3 u_background;

// Fraction of shadow-map taps that see P lit: (2r+1)^2 taps, depth compared per texel (never
// interpolated: an average of depths is not a depth).
float visibility(vec3 p) {
  vec4 clip = u_light_view_projection * vec4(p, 1.0);
  vec3 w = clip.xyz / clip.w * 0.5 + 0.5;
  if (any(lessThan(w.xy, vec2(0.0))) || any(greaterThan(w.xy, vec2(1.0))) || w.z > 1.0) {
    return 1.0;
  }
  ivec2 size = textureSize(u_shadow, 0);
  ivec2 texel = clamp(ivec2(floor(w.xy * vec2(size))), ivec2(0), size - 1);
  float lit = 0.0;
  float taps = 0.0;
  for (int dy = -u_pcf_radius; dy <= u_pcf_radius; ++dy) {
    for (int dx = -u_pcf_radius; dx <= u_pcf_radius; ++dx) {
      ivec2 t = clamp(texel + ivec2(dx, dy), ivec2(0), size - 1);
      lit += w.z <= texelFetch(u_shadow, t, 0).r ? 1.0 : 0.0;
      taps += 1.0;
    }
  }
  return lit / taps;
}

// Bilinear lookup that wraps across the texture's period (pool textures clamp at the edge).
vec3 sample_periodic(sampler2D s, vec2 uv) {
  ivec2 size = textureSize(s, 0);
  vec2 x = uv * vec2(size) - 0.5;
  vec2 f = x - floor(x);
  ivec2 i0 = ivec2(floor(x));
  ivec2 i00 = ((i0 % size) + size) % size;
  ivec2 i11 = (i00 + 1) % size;
  vec3 a = texelFetch(s, i00, 0).rgb;
  vec3 b = texelFetch(s, ivec2(i11.x, i00.y), 0).rgb;
  vec3 c = texelFetch(s, ivec2(i00.x, i11.y), 0).rgb;
  vec3 d = texelFetch(s, i11, 0).rgb;
  return mix(mix(a, b, f.x), mix(c, d, f.x), f.y);
}

// Caustic brightness reaching P: follow the light back up to the water plane and read the
// tileable caustic texture there (mean 1 over a tile, so strength only changes contrast).
vec3 caustic(vec3 p) {
  if (!u_has_caustics || u_light_direction.y >= 0.0 || p.y >= u_water_height) return vec3(1.0);
  float t = (u_water_height - p.y) / -u_light_direction.y;
  vec3 q = p - t * u_light_direction;
  vec3 c = sample_periodic(u_caustics, q.xz / u_caustic_tile);
  return max(vec3(0.0), vec3(1.0) + u_caustic_strength * (c - vec3(1.0)));
}

float quantize_value(float v) {
  if (u_levels <= 1) return v > 0.0 ? 1.0 : 0.0;
  float steps = float(u_levels - 1);
  return floor(v * steps + 0.5) / steps;
}

// G-buffer texels are read exactly (no filtering across an object's edge); inputs of another
// size than the output are addressed proportionally.
vec4 fetch(sampler2D s) {
  ivec2 size = textureSize(s, 0);
  ivec2 texel = ivec2(floor(v_uv * vec2(size)));
  return texelFetch(s, clamp(texel, ivec2(0), size - 1), 0);
}

void main() {
  if (!(fetch(u_id).r >= 0.5)) {  // id 0 (or NaN): background
    o_color = vec4(u_background, 1.0);
    return;
  }
  vec3 p = fetch(u_position).xyz;
  vec3 n = fetch(u_normal).xyz;
  vec3 albedo = max(fetch(u_albedo).rgb, vec3(0.0));
  float len = length(n);
  n = len > 1e-6 ? n / len : vec3(0.0);

  float ndl = max(dot(n, -u_light_direction), 0.0);
  vec3 direct = vec3(0.0);
  if (ndl > 0.0) {
    float vis = u_has_shadow ? visibility(p) : 1.0;
    direct = u_light_color * ndl * vis * caustic(p);
  }
  vec3 lit = albedo * (u_ambient + direct);

  if (u_quantize) {
    float v = max(lit.r, max(lit.g, lit.b));
    lit = v > 0.0 ? lit * (quantize_value(v) / v) : vec3(0.0);
  }
  // NaN or Inf in an input stays local: the pixel goes black instead of spreading.
  if (any(isnan(lit)) || any(isinf(lit))) lit = vec3(0.0);
  o_color = vec4(lit, 1.0);
}
