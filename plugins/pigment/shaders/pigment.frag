// Pigment density variation (Bousseau et al. 2006, seed sec. 3.6). Three densities in turn -
// turbulence (low-frequency fBm), grain (high-frequency Gaussian pigment dispersion) and paper
// (Worley cells) - each modify every colour channel by
//     C' = C (1 - (1 - C)(d - 1)),   d = clamp(1 + weight * n, 0, 2)
// where n is the density texture centred on 0 (an input image's red - 0.5, or procedural).
// d in [0, 2] is exactly the condition for C' to stay in [0, 1] for every C in [0, 1].
//
// Where the textures live:
//  - the canvas (screen anchoring, and the paper always): a dynamic canvas (Cunzi et al. 2003)
//    - two layers of the texture, panned by the camera's yaw and pitch and zoomed by the log
//    of its distance to the target, blended so that the texture follows the view and keeps its
//    on-screen frequency. Without a camera it is the plain screen-space texture.
//  - object anchoring: procedural turbulence and grain evaluated at the world position.
//
// llvmpipe runs both sides of a branch, so what a node does not use must not be in its shader:
// the node compiles a variant with these defines before this text (the defaults below are the
// all-procedural screen variant):
//   AQ_PIGMENT_TURBULENCE, AQ_PIGMENT_GRAIN, AQ_PIGMENT_PAPER: 0 off, 1 input image, 2 procedural
//   AQ_PIGMENT_OBJECT: 1 for object anchoring
//   AQ_PIGMENT_TWO_LAYERS: 1 when the canvas zoom is fractional (two layers to blend)
//   AQ_PIGMENT_PASS: 0 one pass; 1 writes the procedural canvas densities (r turbulence, g grain,
//   b paper) of this view; 2 reads them from u_density instead of computing them. Screen
//   anchoring's procedural densities depend only on the view (canvas pan and zoom), not on the
//   image: pigment.cpp keeps them in a texture while the view stays, so a still camera pays
//   for the noise once.
//   Pass 1 for the `pigment_canvas` node: AQ_PIGMENT_BAKE_INPUTS 1 writes the input textures'
//   densities too (sampled on the canvas), and AQ_PIGMENT_DENSITY_OFFSET 0.5 writes n + 0.5.
#ifndef AQ_PIGMENT_PASS
#define AQ_PIGMENT_PASS 0
#endif
#ifndef AQ_PIGMENT_TURBULENCE
#define AQ_PIGMENT_TURBULENCE 2
#define AQ_PIGMENT_GRAIN 2
#define AQ_PIGMENT_PAPER 2
#define AQ_PIGMENT_OBJECT 0
#define AQ_PIGMENT_TWO_LAYERS 0
#endif

#ifndef AQ_PIGMENT_BAKE_INPUTS
#define AQ_PIGMENT_BAKE_INPUTS 0
#endif
#ifndef AQ_PIGMENT_DENSITY_OFFSET
#define AQ_PIGMENT_DENSITY_OFFSET 0.0
#endif

#include "aquarelle/hdr8.glsl"
#include "aquarelle/noise.glsl"
#include "aquarelle/pigment_density.glsl"

// AQ_PIGMENT_ENCODE_HDR8 1: the output is stored as AQ_FORMAT_RGBA8_HDR (its reader decodes).
#ifndef AQ_PIGMENT_ENCODE_HDR8
#define AQ_PIGMENT_ENCODE_HDR8 0
#endif

in vec2 v_uv;
layout(location = 0) out vec4 o_color;

uniform sampler2D u_image;
uniform sampler2D u_textures[3];   // turbulence, grain, paper (when connected)
uniform sampler2D u_position;      // world position, w = 0 on the background
uniform float u_weights[3];
uniform float u_frequencies[3];    // cells per canvas unit (image height) or per world unit
uniform float u_world_scale;       // world units per unit, object anchoring
uniform float u_seed;
uniform float u_aspect;            // image width / height
uniform vec2 u_pan;                // canvas pan, in image heights
uniform float u_zoom;              // log2 zoom of the canvas

const int TURBULENCE = 0;
const int GRAIN = 1;
const int PAPER = 2;
const int kSourceMode[3] = int[3](AQ_PIGMENT_TURBULENCE, AQ_PIGMENT_GRAIN, AQ_PIGMENT_PAPER);

// Integer offsets (exact in float) that make every source, layer and seed an independent field.
vec2 field_offset(int source, float layer) {
  return mod(vec2(float(source) * 1013.0 + layer * 389.0 + u_seed * 113.0,
                  float(source) * 577.0 + layer * 211.0 + u_seed * 71.0),
             4096.0);
}

// Procedural density texture, centred on 0, at 2D point p (cells).
float procedural2(int source, vec2 p) {
  if (source == TURBULENCE) return 0.5 * aq_fbm2(p, vec2(0.0), 3);
  if (source == GRAIN) return aq_gaussian_noise(floor(p), u_seed) / 6.0;
  return 0.5 - min(aq_worley2(p, vec2(0.0)), 1.0);
}

// One canvas layer: q is in canvas units (image heights, centred), `layer` its absolute index.
// The paper's texture is a height (the `paper` node's, or the procedural raised cells): its
// density is the depth, 0.5 - height, because pigment settles in the paper's valleys (darker)
// and leaves its peaks lighter.
float canvas_layer(int source, vec2 q, float layer) {
  float n;
  if (kSourceMode[source] == 1) {
    // Input textures cover the image once at zoom 0 and repeat beyond (they should tile); other
    // layers are shifted by an irrational fraction of the tile so they do not line up.
    vec2 uv = fract(q / vec2(u_aspect, 1.0) + 0.5 + layer * vec2(0.6180339887, 0.3819660113));
    n = texture(u_textures[source], uv).r - 0.5;
  } else {
    n = procedural2(source, q * u_frequencies[source] + field_offset(source, layer));
  }
  return source == PAPER ? -n : n;
}

#if AQ_PIGMENT_PASS == 2
uniform sampler2D u_density;  // the procedural canvas densities of this view (pass 1)
#endif

float canvas_density(int source, vec2 screen) {
#if AQ_PIGMENT_PASS == 2
  if (kSourceMode[source] == 2) return texelFetch(u_density, ivec2(gl_FragCoord.xy), 0)[source];
#endif
  float base = floor(u_zoom);
  float blend = u_zoom - base;
  // Layer `base + k` is scaled by 2^(k - blend): as the zoom grows by 1 the next layer takes
  // the place of the current one, so the canvas zooms forever without a jump.
  float n0 = canvas_layer(source, (screen + u_pan) * exp2(-blend), base);
#if AQ_PIGMENT_TWO_LAYERS == 0
  return n0;
#else
  float n1 = canvas_layer(source, (screen + u_pan) * exp2(1.0 - blend), base + 1.0);
  float w0 = 1.0 - blend;
  float w1 = blend;
  return (w0 * n0 + w1 * n1) / sqrt(w0 * w0 + w1 * w1);  // keeps the variance of one layer
#endif
}

float object_density(int source, vec3 world) {
  vec3 p = world / u_world_scale * u_frequencies[source];
  vec2 offset = field_offset(source, 0.0);
  if (source == TURBULENCE) {
    float sum = 0.0;
    float amplitude = 1.0;
    float total = 0.0;
    for (int k = 0; k < 3; ++k) {
      sum += amplitude * aq_perlin3(p * exp2(float(k)) + vec3(offset, 0.0), vec3(0.0));
      total += amplitude;
      amplitude *= 0.5;
    }
    return 0.5 * sum / total;
  }
  vec3 cell = floor(p);
  return aq_gaussian_noise(cell.xy + offset, cell.z + u_seed * 4099.0) / 6.0;
}

vec3 modulate(vec3 c, int source, vec2 screen, bool on_object, vec3 world) {
  float n;
#if AQ_PIGMENT_OBJECT == 1
  if (source != PAPER && kSourceMode[source] == 2 && on_object) {
    n = object_density(source, world);
  } else {
    n = canvas_density(source, screen);
  }
#else
  n = canvas_density(source, screen);
#endif
  return aq_pigment_density(c, u_weights[source], n);
}

#if AQ_PIGMENT_PASS == 1
void main() {
  vec2 screen = (v_uv - 0.5) * vec2(u_aspect, 1.0);
  vec4 n = vec4(0.0);
#if AQ_PIGMENT_TURBULENCE == 2 || (AQ_PIGMENT_BAKE_INPUTS && AQ_PIGMENT_TURBULENCE == 1)
  n.r = canvas_density(TURBULENCE, screen);
#endif
#if AQ_PIGMENT_GRAIN == 2 || (AQ_PIGMENT_BAKE_INPUTS && AQ_PIGMENT_GRAIN == 1)
  n.g = canvas_density(GRAIN, screen);
#endif
#if AQ_PIGMENT_PAPER == 2 || (AQ_PIGMENT_BAKE_INPUTS && AQ_PIGMENT_PAPER == 1)
  n.b = canvas_density(PAPER, screen);
#endif
  o_color = vec4(n.rgb + AQ_PIGMENT_DENSITY_OFFSET, 1.0);
}
#else
void main() {
  ivec2 pixel = ivec2(gl_FragCoord.xy);
  vec4 color = texelFetch(u_image, pixel, 0);
  vec2 screen = (v_uv - 0.5) * vec2(u_aspect, 1.0);
#if AQ_PIGMENT_OBJECT == 1
  // The position under the pixel centre, never interpolated across an object's silhouette.
  vec4 position = texelFetch(u_position, ivec2(v_uv * vec2(textureSize(u_position, 0))), 0);
  bool on_object = position.w > 0.0;
#else
  vec4 position = vec4(0.0);
  bool on_object = false;
#endif
  // One call per density with a constant source index, so that every index and mode folds to a
  // constant and unused code disappears.
  vec3 c = color.rgb;
#if AQ_PIGMENT_TURBULENCE != 0
  c = modulate(c, TURBULENCE, screen, on_object, position.xyz);
#endif
#if AQ_PIGMENT_GRAIN != 0
  c = modulate(c, GRAIN, screen, on_object, position.xyz);
#endif
#if AQ_PIGMENT_PAPER != 0
  c = modulate(c, PAPER, screen, on_object, position.xyz);
#endif
  o_color = vec4(c, color.a);
#if AQ_PIGMENT_ENCODE_HDR8
  o_color = aq_hdr8_encode(o_color);
#endif
}
#endif
