// Flat grey-scale and luminance-ordered morphology (erosion and dilation) shared by the `erode`
// and `dilate` plugins: `#define AQ_MORPH_DILATE` (or nothing, for erosion) before
// `#include "aquarelle/morphology.glsl"`. The file holds the whole fragment shader, main()
// included, so the two plugins run literally the same code with one define flipped.
//
// The footprint (a square or a disc of diameter `size`) is described as one horizontal span per
// row offset dy in [-r, r], with half-width w(dy). Because min and max are associative, the
// extreme over the footprint is the extreme, over dy, of the extreme over the row span of
// half-width w(dy). So the work is split in two passes whose cost grows with k, not k^2:
//
//   pass 0 (rows):    image --> span_i(x, y) = extreme over |t| <= w_i of image(x + t, y)
//                               for each distinct half-width w_i (one MRT output each, <= 5)
//   pass 1 (columns): span_* --> out(x, y) = extreme over dy of span_{row_span[dy]}(x, y + dy)
//
// A square has a single span (w_i = r), so pass 0 writes one texture and this is the classic
// separable min/max filter. Lookups clamp to the image (texelFetch of clamped coordinates), which
// for these footprints is the same as restricting the window to the image.
//
// The node compiles one variant per pass, footprint and order, with these defines before the
// plugin's shader text, so that every loop below has a constant trip count and unrolls, and
// every array and sampler index is a constant (dynamic indexing is slow on llvmpipe):
//   AQ_MORPH_PASS         0 rows, 1 columns
//   AQ_MORPH_RADIUS       r = (size - 1) / 2, 1..4
//   AQ_MORPH_SPAN_COUNT   number of distinct row half-widths, 1..5
//   AQ_MORPH_HALF_WIDTHS  int[5](...): the distinct half-widths, ascending (unused: -1)
//   AQ_MORPH_ROW_SPANS    int[9](...): span index of row offset dy at [dy + r]
//   AQ_MORPH_LUMINANCE    0 per channel, 1 luminance order
//   AQ_MORPH_IN_HDR8      1: the input (and pass 0's spans) hold AQ_FORMAT_RGBA8_HDR
//   AQ_MORPH_OUT_HDR8     1: pass 1 writes AQ_FORMAT_RGBA8_HDR
// The encoding is monotone per channel, so per-channel extremes of stored values are the
// stored extremes: only the last write decodes or encodes (the luminance order decodes to
// compare, since luminance mixes channels).
//
//   AQ_MORPH_BLOCKED      1: the square, per-channel, 8-bit fast path (below)
//
// The blocked path (square footprint, per channel, an 8-bit input): pass 0 computes the row
// extremes of a 2 x 2 block of pixels per fragment, reading the 2r + 2 texels of each of its
// two rows once for both columns ((r + 1) / 2 reads per pixel instead of 2r + 1, a quarter of
// the fragments), and stores the four results bit-exactly as packUnorm4x8 words in one RGBA32UI
// texel (x: the block's pixel (0, 0), y: (1, 0), z: (0, 1), w: (1, 1)). Pass 1 reads the
// r + 1 blocks that hold the column of rows y - r .. y + r (two rows per read instead of one)
// and drops the one row of them outside the window. The extremes are the same texels' extremes,
// so the image is bit-identical to the two plain passes.
//
// Orders: 0 = per channel (min/max of each of r, g, b, a separately, the seed's sec. 3.3);
// 1 = luminance order (a total order on colours: Rec.709 luminance, ties broken by r, g, b, a),
// so every output pixel is one of the window's input colours and no new colour appears.

// Without the node's defines (a standalone compile check, an editor preview of the file) the
// shader is the 3x3 square per-channel row pass.
#ifndef AQ_MORPH_PASS
#define AQ_MORPH_PASS 0
#define AQ_MORPH_RADIUS 1
#define AQ_MORPH_SPAN_COUNT 1
#define AQ_MORPH_HALF_WIDTHS int[5](1, -1, -1, -1, -1)
#define AQ_MORPH_ROW_SPANS int[9](0, 0, 0, 0, 0, 0, 0, 0, 0)
#define AQ_MORPH_LUMINANCE 0
#endif
#ifndef AQ_MORPH_IN_HDR8
#define AQ_MORPH_IN_HDR8 0
#define AQ_MORPH_OUT_HDR8 0
#endif
#ifndef AQ_MORPH_BLOCKED
#define AQ_MORPH_BLOCKED 0
#endif
#ifndef AQ_MORPH_IN_BLOCKS
#define AQ_MORPH_IN_BLOCKS 0
#endif
#ifndef AQ_MORPH_OUT_BLOCKS
#define AQ_MORPH_OUT_BLOCKS 0
#endif
// Confinement to regions (the node's `regions` input connected): the window of a pixel holds
// only the pixels of its own region, whose label rides in the alpha channel between passes.
//   AQ_MORPH_CONFINE  1: a tap counts only when its alpha (label) equals the centre pixel's
//   AQ_MORPH_LABEL    1: this pass (a node's first) takes every tap's label from u_regions; 0 in
//                     a node's first pass: the input's alpha holds the labels already (`labels`
//                     = alpha, e.g. cel_light's `alpha` = regions), no region image is read
//   AQ_MORPH_OPAQUE   1: this pass (a node's last, not handed on) writes alpha 1
#ifndef AQ_MORPH_CONFINE
#define AQ_MORPH_CONFINE 0
#endif
#ifndef AQ_MORPH_LABEL
#define AQ_MORPH_LABEL 0
#endif
#ifndef AQ_MORPH_OPAQUE
#define AQ_MORPH_OPAQUE 0
#endif

#include "aquarelle/hdr8.glsl"

in vec2 v_uv;
#if AQ_MORPH_BLOCKED && (AQ_MORPH_PASS == 0 || AQ_MORPH_OUT_BLOCKS || defined(AQ_MORPH_PENDING_RADIUS))
layout(location = 0) out uvec4 o_block;  // four pixels' row extremes, packUnorm4x8 each
#else
layout(location = 0) out vec4 o_color;  // pass 1 result, or span 0 in pass 0
#endif
#if AQ_MORPH_PASS == 0 && AQ_MORPH_SPAN_COUNT > 1
layout(location = 1) out vec4 o_span1;
#endif
#if AQ_MORPH_PASS == 0 && AQ_MORPH_SPAN_COUNT > 2
layout(location = 2) out vec4 o_span2;
#endif
#if AQ_MORPH_PASS == 0 && AQ_MORPH_SPAN_COUNT > 3
layout(location = 3) out vec4 o_span3;
#endif
#if AQ_MORPH_PASS == 0 && AQ_MORPH_SPAN_COUNT > 4
layout(location = 4) out vec4 o_span4;
#endif

const int kHalfWidths[5] = AQ_MORPH_HALF_WIDTHS;
const int kRowSpans[9] = AQ_MORPH_ROW_SPANS;

#if AQ_MORPH_PASS == 0 && !AQ_MORPH_IN_BLOCKS && !defined(AQ_MORPH_PENDING_RADIUS)
uniform sampler2D u_image;
#elif AQ_MORPH_BLOCKED
uniform usampler2D u_blocks;
uniform ivec2 u_image_size;  // the image's size in pixels (the blocks cover it rounded up to even)
#else
uniform sampler2D u_spans[AQ_MORPH_SPAN_COUNT];
#endif

// True when colour a comes strictly before b in the luminance order.
bool aq_morph_luminance_less(vec4 a, vec4 b) {
  const vec3 weights = vec3(0.2126, 0.7152, 0.0722);
#if AQ_MORPH_IN_HDR8
  float la = dot(aq_hdr8_decode(a).rgb, weights);
  float lb = dot(aq_hdr8_decode(b).rgb, weights);
#else
  float la = dot(a.rgb, weights);
  float lb = dot(b.rgb, weights);
#endif
  if (la != lb) return la < lb;
  if (a.r != b.r) return a.r < b.r;
  if (a.g != b.g) return a.g < b.g;
  if (a.b != b.b) return a.b < b.b;
  return a.a < b.a;
}

// Combines the running extreme with a candidate: min for erosion, max for dilation.
vec4 aq_morph_combine(vec4 best, vec4 candidate) {
#if AQ_MORPH_LUMINANCE == 1
#ifdef AQ_MORPH_DILATE
  return aq_morph_luminance_less(best, candidate) ? candidate : best;
#else
  return aq_morph_luminance_less(candidate, best) ? candidate : best;
#endif
#else
#ifdef AQ_MORPH_DILATE
  return max(best, candidate);
#else
  return min(best, candidate);
#endif
#endif
}

// The columns pass's result in the output's format: decoded or encoded only here.
vec4 aq_morph_output(vec4 best) {
#if AQ_MORPH_IN_HDR8 && !AQ_MORPH_OUT_HDR8
  return aq_hdr8_decode(best);
#elif !AQ_MORPH_IN_HDR8 && AQ_MORPH_OUT_HDR8
  return aq_hdr8_encode(best);
#else
  return best;
#endif
}

#if AQ_MORPH_LABEL
#include "aquarelle/region_label.glsl"
uniform sampler2D u_regions;

// The label of the region at `pixel` (aquarelle/region_label.glsl).
float aq_morph_label(ivec2 pixel) {
  ivec2 last = textureSize(u_regions, 0) - 1;
  return aq_region_label(texelFetch(u_regions, clamp(pixel, ivec2(0), last), 0).rgb);
}
#endif

// The running extreme of a window centred on a pixel labelled `centre` with one more tap: a tap
// of another region is left out (AQ_MORPH_CONFINE). The centre is in its own window, so the
// result keeps the centre's label in alpha.
vec4 aq_morph_confined(vec4 best, vec4 candidate, float centre) {
#if AQ_MORPH_BLOCKED && AQ_MORPH_LUMINANCE == 0
  // 8-bit values lie in [0, 1]: a tap of another region is pushed out of reach (+2 under min,
  // -2 under max) instead of selecting four channels, and alpha (the label) is left alone.
  // Fewer operations per tap on llvmpipe, the same bits.
  float away = candidate.a == centre ? 0.0 : 2.0;
#ifdef AQ_MORPH_DILATE
  return vec4(max(best.rgb, candidate.rgb - away), best.a);
#else
  return vec4(min(best.rgb, candidate.rgb + away), best.a);
#endif
#else
  return candidate.a == centre ? aq_morph_combine(best, candidate) : best;
#endif
}

// A node's last write: alpha 1 when confined and not handed on (the labels end with the chain).
vec4 aq_morph_finish(vec4 c) {
#if AQ_MORPH_OPAQUE
  return vec4(c.rgb, 1.0);
#else
  return c;
#endif
}

#if AQ_MORPH_BLOCKED && (AQ_MORPH_IN_BLOCKS || AQ_MORPH_OUT_BLOCKS || defined(AQ_MORPH_PENDING_RADIUS))
// Blocks to blocks along one axis: one fragment per 2 x 2 block reads the blocks at offsets
// kLo .. kHi along the pass's axis, which hold the pixels 2b - kReach .. 2b + 1 + kReach of
// both of the block's lines (kReach: how far the pass reads).
#ifdef AQ_MORPH_PENDING_RADIUS
const int kReach = AQ_MORPH_PENDING_RADIUS + AQ_MORPH_RADIUS;
#else
const int kReach = AQ_MORPH_RADIUS;
#endif
const int kLo = -((kReach + 1) >> 1);
const int kHi = (kReach + 1) >> 1;
const int kSpan = kHi - kLo + 1;
#if AQ_MORPH_PASS == 0
const ivec2 kAxis = ivec2(1, 0);
#else
const ivec2 kAxis = ivec2(0, 1);
#endif

// The fragment's block index along the axis, the image's extent along it, and the blocks.
void aq_morph_axis_blocks(out int b, out int extent, out uvec4 words[kSpan]) {
  ivec2 block = ivec2(gl_FragCoord.xy);
  b = AQ_MORPH_PASS == 0 ? block.x : block.y;
  extent = AQ_MORPH_PASS == 0 ? u_image_size.x : u_image_size.y;
  ivec2 last_block = (u_image_size - 1) >> 1;
  for (int k = 0; k < kSpan; ++k)
    words[k] = texelFetch(u_blocks, clamp(block + (kLo + k) * kAxis, ivec2(0), last_block), 0);
}

// Pixel `along` (0 or 1 along the pass's axis) of line `across` (0 or 1) of a block's words.
uint aq_morph_word(uvec4 words, int along, int across) {
#if AQ_MORPH_PASS == 0
  return across == 0 ? (along == 0 ? words.x : words.y) : (along == 0 ? words.z : words.w);
#else
  return across == 0 ? (along == 0 ? words.x : words.z) : (along == 0 ? words.y : words.w);
#endif
}

// The four results in the block's word order (indexed [2 * across + along]).
uvec4 aq_morph_block_out(uint results[4]) {
#if AQ_MORPH_PASS == 0
  return uvec4(results[0], results[1], results[2], results[3]);
#else
  // along runs down the columns here: x = (0, 0), y = (1, 0), z = (0, 1), w = (1, 1).
  return uvec4(results[0], results[2], results[1], results[3]);
#endif
}
#endif

#if AQ_MORPH_BLOCKED && defined(AQ_MORPH_PENDING_RADIUS)
// Neighbourhood fusion (AQ_PORT_DEFER_AXIS): the writer's last 1D pass, left undone (min, or
// max with AQ_MORPH_PENDING_DILATE 1, of radius r1 = AQ_MORPH_PENDING_RADIUS), then this
// node's own pass along the same axis (radius r2 = AQ_MORPH_RADIUS, 0: the writer's pass
// alone), in one pass from blocks to blocks. The intermediate of the writer's pass is computed
// at the 2 r2 + 2 pixels around the block that the own window reads; both windows leave out
// pixels outside the image, as the two passes would (each clamps its lookups), so the result
// is the very bits of the two passes.
vec4 aq_morph_pending_combine(vec4 best, vec4 candidate) {
#if AQ_MORPH_PENDING_DILATE
  return max(best, candidate);
#else
  return min(best, candidate);
#endif
}

void main() {
  int b, extent;
  uvec4 words[kSpan];
  aq_morph_axis_blocks(b, extent, words);
  uint results[4];
  for (int across = 0; across < 2; ++across) {
    // The pixels 2b - kReach + i, each unpacked once; outside the image the identity of the
    // writer's extreme, which leaves them out of its windows (constant bounds: the loops unroll
    // and every index is a constant).
    vec4 pixels[2 * kReach + 2];
    for (int i = 0; i < 2 * kReach + 2; ++i) {
      int d = i - kReach;
      int pixel = 2 * b + d;
      vec4 v = unpackUnorm4x8(aq_morph_word(words[((d - 2 * kLo) >> 1)], (d - 2 * kLo) & 1,
                                            across));
      pixels[i] = pixel >= 0 && pixel < extent ? v : vec4(AQ_MORPH_PENDING_DILATE != 0 ? 0.0 : 1.0);
    }
    // The writer's pass at the pixels 2b - r2 + j; outside the image the identity of this
    // node's extreme, which leaves them out of its window.
    vec4 first[2 * AQ_MORPH_RADIUS + 2];
    for (int j = 0; j < 2 * AQ_MORPH_RADIUS + 2; ++j) {
#if AQ_MORPH_CONFINE
      // Only the taps of the centre's region (the labels the writer left in alpha).
      vec4 best = pixels[j + AQ_MORPH_PENDING_RADIUS];
      float centre = best.a;
      for (int t = 0; t <= 2 * AQ_MORPH_PENDING_RADIUS; ++t) {
        // As aq_morph_confined: a tap of another region pushed out of reach of the extreme.
        float away = pixels[j + t].a == centre ? 0.0 : 2.0;
#if AQ_MORPH_PENDING_DILATE
        best.rgb = max(best.rgb, pixels[j + t].rgb - away);
#else
        best.rgb = min(best.rgb, pixels[j + t].rgb + away);
#endif
      }
#else
      vec4 best = pixels[j];
      for (int t = 1; t <= 2 * AQ_MORPH_PENDING_RADIUS; ++t)
        best = aq_morph_pending_combine(best, pixels[j + t]);
#endif
      int pixel = 2 * b + j - AQ_MORPH_RADIUS;
#ifdef AQ_MORPH_DILATE
      first[j] = pixel >= 0 && pixel < extent ? best : vec4(0.0);
#else
      first[j] = pixel >= 0 && pixel < extent ? best : vec4(1.0);
#endif
    }
    for (int along = 0; along < 2; ++along) {
#if AQ_MORPH_CONFINE
      vec4 best = first[along + AQ_MORPH_RADIUS];
      float centre = best.a;
      for (int s = 0; s <= 2 * AQ_MORPH_RADIUS; ++s)
        best = aq_morph_confined(best, first[along + s], centre);
      results[2 * across + along] = packUnorm4x8(aq_morph_finish(best));
#else
      vec4 best = first[along];
      for (int s = 1; s <= 2 * AQ_MORPH_RADIUS; ++s) best = aq_morph_combine(best, first[along + s]);
      results[2 * across + along] = packUnorm4x8(best);
#endif
    }
  }
  o_block = aq_morph_block_out(results);
}
#elif AQ_MORPH_BLOCKED && (AQ_MORPH_OUT_BLOCKS || (AQ_MORPH_IN_BLOCKS && AQ_MORPH_PASS == 0))
// Blocks to blocks: one fragment per 2 x 2 block computes its four pixels' extremes along the
// pass's axis from the blocks that hold the pixels 2b - r .. 2b + 1 + r of both of the block's
// lines. Pixels outside the image are left out of the window (the same as clamping the lookups,
// as everywhere in this file). A columns pass from blocks into pixels (the last node of a
// handed-over chain, when nothing reads blocks after it) is the plain blocked columns pass below.

#if AQ_MORPH_CONFINE
// Confined: each line's 2r + 2 pixels unpacked once (labels from u_regions in a node's first
// pass), then each of the block's two pixels takes the taps of its own region.
void main() {
  int b, extent;
  uvec4 words[kSpan];
  aq_morph_axis_blocks(b, extent, words);
  ivec2 block = ivec2(gl_FragCoord.xy);
  uint results[4];
  for (int across = 0; across < 2; ++across) {
    vec4 pixels[2 * AQ_MORPH_RADIUS + 2];
    bool inside[2 * AQ_MORPH_RADIUS + 2];
    for (int i = 0; i < 2 * AQ_MORPH_RADIUS + 2; ++i) {
      int d = i - AQ_MORPH_RADIUS;
      int pixel = 2 * b + d;
      vec4 v = unpackUnorm4x8(aq_morph_word(words[((d - 2 * kLo) >> 1)], (d - 2 * kLo) & 1,
                                            across));
#if AQ_MORPH_LABEL
      v.a = aq_morph_label(AQ_MORPH_PASS == 0 ? ivec2(pixel, 2 * block.y + across)
                                              : ivec2(2 * block.x + across, pixel));
#endif
      pixels[i] = v;
      inside[i] = pixel >= 0 && pixel < extent;
    }
    for (int along = 0; along < 2; ++along) {
      vec4 best = pixels[along + AQ_MORPH_RADIUS];
      float centre = best.a;
      for (int t = 0; t <= 2 * AQ_MORPH_RADIUS; ++t)
        best = inside[along + t] ? aq_morph_confined(best, pixels[along + t], centre) : best;
      results[2 * across + along] = packUnorm4x8(aq_morph_finish(aq_morph_output(best)));
    }
  }
  o_block = aq_morph_block_out(results);
}
#else
void main() {
  int b, extent;
  uvec4 words[kSpan];
  aq_morph_axis_blocks(b, extent, words);
  uint results[4];
  for (int across = 0; across < 2; ++across) {
    for (int along = 0; along < 2; ++along) {
#ifdef AQ_MORPH_DILATE
      vec4 best = vec4(0.0);
#else
      vec4 best = vec4(1.0);
#endif
      // Constant bounds, so the loops unroll and every index below is a constant.
      for (int t = 0; t <= 2 * AQ_MORPH_RADIUS; ++t) {
        int d = along - AQ_MORPH_RADIUS + t;
        int pixel = 2 * b + d;
        // d - 2 kLo >= 0, so the shift is a floor division.
        vec4 v = unpackUnorm4x8(aq_morph_word(words[((d - 2 * kLo) >> 1)], (d - 2 * kLo) & 1,
                                              across));
        best = pixel >= 0 && pixel < extent ? aq_morph_combine(best, v) : best;
      }
      results[2 * across + along] = packUnorm4x8(aq_morph_output(best));
    }
  }
  o_block = aq_morph_block_out(results);
}
#endif
#elif AQ_MORPH_BLOCKED && AQ_MORPH_PASS == 0 && AQ_MORPH_CONFINE
// Confined rows from pixels: the 2r + 2 pixels of each of the block's rows read once (labels
// from u_regions), then each of its two pixels takes the taps of its own region.
void main() {
  ivec2 block = ivec2(gl_FragCoord.xy);
  ivec2 last = textureSize(u_image, 0) - 1;
  int x0 = 2 * block.x;
  uvec4 words;
  for (int half_row = 0; half_row < 2; ++half_row) {
    int y = min(2 * block.y + half_row, last.y);
    vec4 pixels[2 * AQ_MORPH_RADIUS + 2];
    for (int i = 0; i < 2 * AQ_MORPH_RADIUS + 2; ++i) {
      ivec2 at = ivec2(clamp(x0 - AQ_MORPH_RADIUS + i, 0, last.x), y);
      pixels[i] = texelFetch(u_image, at, 0);
#if AQ_MORPH_LABEL
      pixels[i].a = aq_morph_label(at);
#endif
    }
    uint results[2];
    for (int k = 0; k < 2; ++k) {
      vec4 best = pixels[k + AQ_MORPH_RADIUS];
      float centre = best.a;
      for (int t = 0; t <= 2 * AQ_MORPH_RADIUS; ++t)
        best = aq_morph_confined(best, pixels[k + t], centre);
      results[k] = packUnorm4x8(best);
    }
    if (half_row == 0) {
      words.xy = uvec2(results[0], results[1]);
    } else {
      words.zw = uvec2(results[0], results[1]);
    }
  }
  o_block = words;
}
#elif AQ_MORPH_BLOCKED && AQ_MORPH_PASS == 0
void main() {
  ivec2 block = ivec2(gl_FragCoord.xy);
  ivec2 last = textureSize(u_image, 0) - 1;
  int x0 = 2 * block.x;
  uvec4 words;
  for (int half_row = 0; half_row < 2; ++half_row) {
    int y = min(2 * block.y + half_row, last.y);
    // Columns x0 - r .. x0 + 1 + r: the inner 2r for both pixels, one outer texel each.
    vec4 inner = texelFetch(u_image, ivec2(clamp(x0, 0, last.x), y), 0);
    inner = aq_morph_combine(inner, texelFetch(u_image, ivec2(min(x0 + 1, last.x), y), 0));
    for (int t = 1; t < AQ_MORPH_RADIUS; ++t) {
      inner = aq_morph_combine(inner, texelFetch(u_image, ivec2(max(x0 - t, 0), y), 0));
      inner = aq_morph_combine(inner, texelFetch(u_image, ivec2(min(x0 + 1 + t, last.x), y), 0));
    }
#if AQ_MORPH_RADIUS == 0
    // Each pixel alone: the node only packs its pixels into blocks.
    uint a = packUnorm4x8(texelFetch(u_image, ivec2(clamp(x0, 0, last.x), y), 0));
    uint b = packUnorm4x8(texelFetch(u_image, ivec2(min(x0 + 1, last.x), y), 0));
#else
    vec4 left = texelFetch(u_image, ivec2(max(x0 - AQ_MORPH_RADIUS, 0), y), 0);
    vec4 right = texelFetch(u_image, ivec2(min(x0 + 1 + AQ_MORPH_RADIUS, last.x), y), 0);
    uint a = packUnorm4x8(aq_morph_combine(inner, left));
    uint b = packUnorm4x8(aq_morph_combine(inner, right));
#endif
    if (half_row == 0) {
      words.xy = uvec2(a, b);
    } else {
      words.zw = uvec2(a, b);
    }
  }
  o_block = words;
}
#elif AQ_MORPH_BLOCKED
void main() {
  ivec2 p = ivec2(gl_FragCoord.xy);
  int last_block = (u_image_size.y - 1) >> 1;
  bool odd_column = (p.x & 1) == 1;
  int first = max(p.y - AQ_MORPH_RADIUS, 0), last = min(p.y + AQ_MORPH_RADIUS, u_image_size.y - 1);
  int b0 = (p.y - AQ_MORPH_RADIUS) >> 1;
#ifdef AQ_MORPH_DILATE
  vec4 best = vec4(0.0);  // the identity of max on unorm values
#else
  vec4 best = vec4(1.0);  // the identity of min on unorm values
#endif
#if AQ_MORPH_CONFINE
  uvec4 own = texelFetch(u_blocks, p >> 1, 0);
  uvec2 own_column = odd_column ? own.yw : own.xz;
  float centre = unpackUnorm4x8((p.y & 1) == 0 ? own_column.x : own_column.y).a;
#endif
  for (int k = 0; k <= AQ_MORPH_RADIUS; ++k) {
    int b = clamp(b0 + k, 0, last_block);
    uvec4 words = texelFetch(u_blocks, ivec2(p.x >> 1, b), 0);
    uvec2 column = odd_column ? words.yw : words.xz;
    // The block's two rows, each only when inside the window (clamped to the image).
    int top = 2 * b, bottom = 2 * b + 1;
    vec4 upper = unpackUnorm4x8(column.x), lower = unpackUnorm4x8(column.y);
#if AQ_MORPH_CONFINE
    best = top >= first && top <= last ? aq_morph_confined(best, upper, centre) : best;
    best = bottom >= first && bottom <= last ? aq_morph_confined(best, lower, centre) : best;
#else
    best = top >= first && top <= last ? aq_morph_combine(best, upper) : best;
    best = bottom >= first && bottom <= last ? aq_morph_combine(best, lower) : best;
#endif
  }
  o_color = aq_morph_finish(aq_morph_output(best));
}
#elif AQ_MORPH_PASS == 0
void main() {
  ivec2 p = ivec2(gl_FragCoord.xy);
  int last = textureSize(u_image, 0).x - 1;
  vec4 spans[5];
  vec4 best = texelFetch(u_image, p, 0);
#if AQ_MORPH_LABEL
  best.a = aq_morph_label(p);
#endif
  float centre = best.a;
  // Grow the span outwards one step at a time and record it when it reaches each half-width.
  for (int t = 0; t <= AQ_MORPH_RADIUS; ++t) {
    if (t > 0) {
#if AQ_MORPH_CONFINE
      ivec2 right = ivec2(min(p.x + t, last), p.y), left = ivec2(max(p.x - t, 0), p.y);
      vec4 r = texelFetch(u_image, right, 0), l = texelFetch(u_image, left, 0);
#if AQ_MORPH_LABEL
      r.a = aq_morph_label(right);
      l.a = aq_morph_label(left);
#endif
      best = aq_morph_confined(aq_morph_confined(best, r, centre), l, centre);
#else
      best = aq_morph_combine(best, texelFetch(u_image, ivec2(min(p.x + t, last), p.y), 0));
      best = aq_morph_combine(best, texelFetch(u_image, ivec2(max(p.x - t, 0), p.y), 0));
#endif
    }
    for (int i = 0; i < AQ_MORPH_SPAN_COUNT; ++i) {
      if (kHalfWidths[i] == t) spans[i] = best;
    }
  }
  o_color = spans[0];
#if AQ_MORPH_SPAN_COUNT > 1
  o_span1 = spans[1];
#endif
#if AQ_MORPH_SPAN_COUNT > 2
  o_span2 = spans[2];
#endif
#if AQ_MORPH_SPAN_COUNT > 3
  o_span3 = spans[3];
#endif
#if AQ_MORPH_SPAN_COUNT > 4
  o_span4 = spans[4];
#endif
}
#else
void main() {
  ivec2 p = ivec2(gl_FragCoord.xy);
  int last = textureSize(u_spans[0], 0).y - 1;
  vec4 best = texelFetch(u_spans[kRowSpans[AQ_MORPH_RADIUS]], p, 0);
  float centre = best.a;
  for (int dy = 1; dy <= AQ_MORPH_RADIUS; ++dy) {
    ivec2 up = ivec2(p.x, min(p.y + dy, last));
    ivec2 down = ivec2(p.x, max(p.y - dy, 0));
    vec4 above = texelFetch(u_spans[kRowSpans[AQ_MORPH_RADIUS + dy]], up, 0);
    vec4 below = texelFetch(u_spans[kRowSpans[AQ_MORPH_RADIUS - dy]], down, 0);
#if AQ_MORPH_CONFINE
    best = aq_morph_confined(aq_morph_confined(best, above, centre), below, centre);
#else
    best = aq_morph_combine(aq_morph_combine(best, above), below);
#endif
  }
  o_color = aq_morph_finish(aq_morph_output(best));
}
#endif
