// Deferred light and cel shading (Paré-Vogt & Chaid §2.3 "Light" pass and §3.1):
//   lit  = albedo * (ambient + light * max(N.L, 0) * visibility * caustic)
//   v    = max(r, g, b)                         (HSV value)
//   e    = srgb(v)  (display space, the default)  or  v  (space = linear)
//   k    = floor(e * (levels - 1) + 0.5),  k >= 1 when v > 0 (floor, the default)
//   v'   = srgb^-1(k / (levels - 1))  (or k / (levels - 1))    (levels = 1: v' = 1)
//   out  = lit * v' / v                         (hue and saturation kept exactly)
// Quantised in display space as the seed did (it quantised display values) and with a floor, a
// lit surface whose albedo is not black never renders black (issue 37: in linear light every
// value below ~45 % display grey rounded to 0).
// Scaling rgb by v'/v is the HSV round trip with a new value, without the hue arithmetic, so
// grey, black and values above 1 need no special case. Output stays linear HDR.
//
// Two outputs from one pass: o_color with caustics, o_plain the same light without them (the
// source `edge` looks at, so caustic patterns draw no outlines).
//
// cel_light.cpp prepends the variant (llvmpipe runs both sides of a branch on a uniform):
//   AQ_SURFACE   1: normal, albedo, id and depth from the packed `surface` (one read instead of
//                four), the position rebuilt from the depth on the camera's ray through the
//                texel's centre
//   AQ_HAS_SHADOW, AQ_HAS_CAUSTICS, AQ_QUANTIZE  0 or 1
//   AQ_QUANTIZE_DISPLAY 1: levels are steps of the sRGB-encoded value (0: of the linear value)
//   AQ_QUANTIZE_FLOOR   1: a pixel with v > 0 keeps at least the first level above black
//   AQ_PLAIN_REGIONS    1: o_plain holds the object regions (a colour per id) instead of the light
//   AQ_ALPHA_LABELS     1: o_color's alpha holds the label of the pixel's region (the hash erode
//                       and dilate take of the region colour) instead of 1
//   AQ_PCF_RADIUS                                0..4
//   AQ_SAME_SIZE   1 when every g-buffer input has the output's size (read at gl_FragCoord)
//   AQ_ENCODE_HDR8 1 when `image` is stored as AQ_FORMAT_RGBA8_HDR (aquarelle/hdr8.glsl)
#ifndef AQ_PLAIN_REGIONS
#define AQ_PLAIN_REGIONS 0
#endif
#ifndef AQ_ALPHA_LABELS
#define AQ_ALPHA_LABELS 0
#endif
#include "aquarelle/gbuffer_surface.glsl"
#include "aquarelle/hdr8.glsl"
#include "aquarelle/region_label.glsl"
in vec2 v_uv;
layout(location = 0) out vec4 o_color;
layout(location = 1) out vec4 o_plain;

#if AQ_SURFACE
uniform usampler2D u_surface;
// The camera's ray through texel t of the surface is u_ray0 + t.x u_ray_dx + t.y u_ray_dy,
// scaled so that its component along the view axis is 1 (cel_light.cpp, from camera_rays).
uniform vec3 u_eye;
uniform vec3 u_ray0;
uniform vec3 u_ray_dx;
uniform vec3 u_ray_dy;
#else
uniform sampler2D u_position;
uniform sampler2D u_normal;
uniform sampler2D u_albedo;
uniform sampler2D u_id;
#endif
uniform sampler2D u_shadow;
uniform sampler2D u_caustics;  // bound with a repeating sampler: the texture is one period

uniform mat4 u_light_view_projection;
uniform vec3 u_light_direction;  // direction light travels, unit
uniform vec3 u_light_color;
uniform vec3 u_ambient;

uniform float u_water_height;
uniform float u_caustic_tile;  // world units per caustic texture period
uniform float u_caustic_strength;

uniform int u_levels;
uniform vec3 u_background;
uniform bool u_environment;  // background from the albedo target (the scene's environment)

#if AQ_HAS_SHADOW
// Fraction of shadow-map taps that see P lit: (2r+1)^2 texels around P's texel, depth compared
// per texel (never interpolated: an average of depths is not a depth). Texels beyond the edge
// repeat the edge texel (the sampler clamps), as clamping the index would.
float visibility(vec3 p) {
  vec4 clip = u_light_view_projection * vec4(p, 1.0);
  vec3 w = clip.xyz / clip.w * 0.5 + 0.5;
  if (any(lessThan(w.xy, vec2(0.0))) || any(greaterThan(w.xy, vec2(1.0))) || w.z > 1.0) {
    return 1.0;
  }
  vec2 size = vec2(textureSize(u_shadow, 0));
  vec2 texel = clamp(floor(w.xy * size), vec2(0.0), size - 1.0);
#if AQ_PCF_RADIUS == 1
  // The 3x3 texels from four gathers (2x2 texels each, around the corners of the centre
  // texel); components x = (i0, j1), y = (i1, j1), z = (i1, j0), w = (i0, j0).
  vec2 inv = 1.0 / size;
  vec4 g00 = step(vec4(w.z), textureGather(u_shadow, (texel + vec2(0.0, 0.0)) * inv));
  vec4 g10 = step(vec4(w.z), textureGather(u_shadow, (texel + vec2(1.0, 0.0)) * inv));
  vec4 g01 = step(vec4(w.z), textureGather(u_shadow, (texel + vec2(0.0, 1.0)) * inv));
  vec4 g11 = step(vec4(w.z), textureGather(u_shadow, (texel + vec2(1.0, 1.0)) * inv));
  float lit = dot(g00, vec4(1.0)) + g10.z + g10.y + g01.x + g01.y + g11.y;
  return lit / 9.0;
#else
  ivec2 t0 = ivec2(texel);
  ivec2 last = ivec2(size) - 1;
  float lit = 0.0;
  for (int dy = -AQ_PCF_RADIUS; dy <= AQ_PCF_RADIUS; ++dy) {
    for (int dx = -AQ_PCF_RADIUS; dx <= AQ_PCF_RADIUS; ++dx) {
      ivec2 t = clamp(t0 + ivec2(dx, dy), ivec2(0), last);
      lit += w.z <= texelFetch(u_shadow, t, 0).r ? 1.0 : 0.0;
    }
  }
  const float taps = float((2 * AQ_PCF_RADIUS + 1) * (2 * AQ_PCF_RADIUS + 1));
  return lit / taps;
#endif
}
#endif

#if AQ_HAS_CAUSTICS
// Caustic brightness reaching P: follow the light back up to the water plane and read the
// tileable caustic texture there (mean 1 over a tile, so strength only changes contrast).
vec3 caustic(vec3 p) {
  if (u_light_direction.y >= 0.0 || p.y >= u_water_height) return vec3(1.0);
  float t = (u_water_height - p.y) / -u_light_direction.y;
  vec3 q = p - t * u_light_direction;
  vec3 c = texture(u_caustics, q.xz / u_caustic_tile).rgb;
  return max(vec3(0.0), vec3(1.0) + u_caustic_strength * (c - vec3(1.0)));
}
#endif

#ifndef AQ_QUANTIZE_DISPLAY
#define AQ_QUANTIZE_DISPLAY 1
#define AQ_QUANTIZE_FLOOR 1
#endif

#if AQ_QUANTIZE_DISPLAY
// The sRGB transfer curve (IEC 61966-2-1, the display of ocio/config.ocio), continued above 1
// by the same power law so HDR values keep their steps.
float srgb_encode(float v) {
  return v <= 0.0031308 ? 12.92 * v : 1.055 * pow(v, 1.0 / 2.4) - 0.055;
}
float srgb_decode(float e) {
  return e <= 0.04045 ? e / 12.92 : pow((e + 0.055) / 1.055, 2.4);
}
#endif

float quantize_value(float v) {
  if (u_levels <= 1) return v > 0.0 ? 1.0 : 0.0;
  float steps = float(u_levels - 1);
#if AQ_QUANTIZE_DISPLAY
  float k = floor(srgb_encode(v) * steps + 0.5);
#else
  float k = floor(v * steps + 0.5);
#endif
#if AQ_QUANTIZE_FLOOR
  k = v > 0.0 ? max(k, 1.0) : k;
#endif
#if AQ_QUANTIZE_DISPLAY
  return srgb_decode(k / steps);
#else
  return k / steps;
#endif
}

vec3 cel(vec3 lit) {
#if AQ_QUANTIZE
  float v = max(lit.r, max(lit.g, lit.b));
  lit = v > 0.0 ? lit * (quantize_value(v) / v) : vec3(0.0);
#endif
  // NaN or Inf in an input stays local: the pixel goes black instead of spreading.
  if (any(isnan(lit)) || any(isinf(lit))) lit = vec3(0.0);
  return lit;
}

// G-buffer texels are read exactly (no filtering across an object's edge); inputs of another
// size than the output are addressed proportionally.
ivec2 texel_of(ivec2 size) {
#if AQ_SAME_SIZE
  return ivec2(gl_FragCoord.xy);
#else
  return clamp(ivec2(floor(v_uv * vec2(size))), ivec2(0), size - 1);
#endif
}

vec4 fetch(sampler2D s) {
  return texelFetch(s, texel_of(textureSize(s, 0)), 0);
}

#if AQ_SURFACE
// The surface at this pixel and the world point the g-buffer saw there: the point at view depth
// z on the ray through the texel's centre, which is where the g-buffer interpolated its position
// (planar triangles, perspective-correct), to float rounding.
aq_surface fetch_surface(out vec3 position) {
  ivec2 t = texel_of(textureSize(u_surface, 0));
  aq_surface surface = aq_surface_unpack(texelFetch(u_surface, t, 0));
  position = u_eye + surface.depth * (u_ray0 + float(t.x) * u_ray_dx + float(t.y) * u_ray_dy);
  return surface;
}
#endif

// Every pixel computes the light and background pixels select their colour at the end: on
// llvmpipe a branch on per-pixel data runs both sides for the whole block anyway, so an early
// return for the background only added its own reads (measured: the pass 30 -> 26 ms at 720p).
void main() {
#if AQ_SURFACE
  vec3 p;
  aq_surface surface = fetch_surface(p);
  float surface_id = surface.id;
  bool background = !(surface.id >= 0.5);  // id 0 (or NaN)
  vec3 albedo = max(surface.albedo, vec3(0.0));
  vec3 n = surface.normal;
#else
  float surface_id = fetch(u_id).r;
  bool background = !(surface_id >= 0.5);
  vec3 albedo = max(fetch(u_albedo).rgb, vec3(0.0));
  vec3 n = fetch(u_normal).xyz;
  vec3 p = fetch(u_position).xyz;
#endif
  float len = length(n);
  n = len > 1e-6 ? n / len : vec3(0.0);

  float ndl = max(dot(n, -u_light_direction), 0.0);
  vec3 direct = vec3(0.0);
  vec3 caustic_factor = vec3(1.0);
  if (ndl > 0.0) {
#if AQ_HAS_SHADOW
    direct = u_light_color * (ndl * visibility(p));
#else
    direct = u_light_color * ndl;
#endif
#if AQ_HAS_CAUSTICS
    caustic_factor = caustic(p);
#endif
  }
  vec4 lit = vec4(cel(albedo * (u_ambient + direct * caustic_factor)), 1.0);
  vec4 plain = vec4(cel(albedo * (u_ambient + direct)), 1.0);
  vec4 behind = vec4(u_environment ? albedo : u_background, 1.0);
  o_color = background ? behind : lit;
  // Where washes meet: one flat colour per object id (0 on the background), far apart for
  // neighbouring ids, so an edge detector on it finds the objects' outlines and nothing inside
  // them (no cel bands, no caustics).
  vec3 region = aq_region_colour(background ? 0.0 : surface_id);
#if AQ_ALPHA_LABELS
  // The label as erode and dilate would hash it from `plain` = regions, stored in 8 bits: the
  // colour rounded to bytes first, as the 8-bit region image they would read holds it.
  o_color.a = aq_region_label(region);
#endif
#if AQ_PLAIN_REGIONS
  o_plain = vec4(region, 1.0);
#else
  o_plain = background ? behind : plain;
#endif
#if AQ_ENCODE_HDR8
  o_color = aq_hdr8_encode(o_color);
#endif
}
