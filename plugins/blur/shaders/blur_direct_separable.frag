// Variable blur in two passes for σmax up to 2 px (the `separable` direct kernel, final quality):
// pass AQ_AXIS 0 blurs along rows, pass 1 along columns, each pixel with the sampled Gaussian of
// its own σ, truncated at AQ_RADIUS taps per side and normalised over them. Where σ is constant
// over a pixel's column of taps this is the one-pass truncated Gaussian (blur_direct.frag)
// exactly; where it changes within AQ_RADIUS pixels (depth edges) the column mixes rows blurred
// with their neighbours' σ. It reads 2·(AQ_RADIUS/2 + 1) + 2 texels per pixel in all (the
// strength's depth read in each pass) instead of (AQ_RADIUS + 1)² + 1 in one pass: on llvmpipe
// the second pass costs less than the 16 fetches it saves (README, cost).
// Per axis the taps 2k−1 and 2k are one bilinear fetch as in blur_direct.frag.
// blur.cpp prepends AQ_RADIUS, AQ_AXIS and AQ_HAS_DEPTH and the strength function, and
// AQ_DECODE_HDR8 / AQ_ENCODE_HDR8 when u_image / the target hold AQ_FORMAT_RGBA8_HDR. An encoded
// image cannot be filtered by the hardware (it would mix codes, not light): every tap is then
// its own texelFetch, decoded, with the weights of the bilinear pairs' two taps. On llvmpipe
// those 2·(AQ_RADIUS/2) + 1 8-bit fetches cost less than AQ_RADIUS/2 + 1 float ones.
// Blocks (AQ_BLOCKS 1, an encoded input, blur.cpp): the rows pass computes a 2 x 2 block of
// pixels per fragment and stores it as AQ_FORMAT_RGBA8_HDR_BLOCKS (plugin.h); each of its two
// rows reads the 2·AQ_RADIUS + 2 texels around both columns once, so a pixel costs
// AQ_RADIUS + 1 reads instead of 2·AQ_RADIUS + 1, in a quarter of the fragments. The columns
// pass then reads the AQ_RADIUS + 1 blocks that hold its 2·AQ_RADIUS + 1 rows (two rows a read).
// Every pixel sums the same decoded taps in the same order as without blocks, and the words are
// the bytes an RGBA8 target would store, so the image is bit-identical.
// Blocks in (AQ_BLOCKS_IN 1: the input itself in blocks, from a writer that makes them, such as
// the wobble): the rows pass reads the AQ_RADIUS + 1 blocks that hold both its rows' taps
// instead of 2·AQ_RADIUS + 2 texels per row; the taps are the same words.
#include "aquarelle/hdr8.glsl"
#ifndef AQ_DECODE_HDR8
#define AQ_DECODE_HDR8 0
#endif
#ifndef AQ_ENCODE_HDR8
#define AQ_ENCODE_HDR8 0
#endif
#ifndef AQ_BLOCKS
#define AQ_BLOCKS 0
#endif
#ifndef AQ_BLOCKS_IN
#define AQ_BLOCKS_IN 0
#endif

#if AQ_BLOCKS && AQ_AXIS == 0
layout(location = 0) out uvec4 o_block;  // pixels (0, 0), (1, 0), (0, 1), (1, 1) of the block
#else
layout(location = 0) out vec4 o_color;
#endif

#if AQ_BLOCKS && (AQ_AXIS == 1 || AQ_BLOCKS_IN)
uniform usampler2D u_blocks;  // the rows pass's blocks, or the input's (AQ_BLOCKS_IN)
uniform ivec2 u_image_size;   // the image's size in pixels
#else
uniform sampler2D u_image;
#endif
uniform float u_sigma;  // σ at strength 1, working pixels

float blur_strength(vec2 frag);

const int kPairs = AQ_RADIUS / 2;
const vec2 kAxis = AQ_AXIS == 0 ? vec2(1.0, 0.0) : vec2(0.0, 1.0);

// log2 q for the pixel at `frag`, q = exp(-1 / (2σ²)) the ratio of the first weight to the
// centre's; σ = 0 makes every weight but the centre's 0 (a select, not a branch).
float log2_ratio(vec2 frag) {
  float sigma = u_sigma * blur_strength(frag);
  return sigma > 0.0 ? -0.7213475204444817 / (sigma * sigma) : -1.0e30;
}

#if AQ_DECODE_HDR8
const int kTaps = 2 * kPairs;  // decoded taps per side
// The pixel at `frag` blurred from its decoded taps along the axis: row[kTaps] is the pixel,
// row[kTaps ± t] the pixels t ahead and behind.
vec4 blur_row(vec2 frag, vec4 row[2 * kTaps + 1]) {
  float log2_q = log2_ratio(frag);
  vec4 centre = row[kTaps];
  vec4 sum = centre;
  float norm = 1.0;
  float first_weight = 0.0;
  for (int t = 1; t <= kTaps; ++t) {
    float weight = exp2(float(t * t) * log2_q);
    sum += weight * (row[kTaps + t] + row[kTaps - t]);
    norm += 2.0 * weight;
    if (t == 1) first_weight = weight;
  }
  // Every neighbour weight underflowed: the input itself, exactly (no 0 · ∞ from a neighbour).
  return first_weight > 0.0 ? sum / norm : centre;
}
#endif

#if AQ_BLOCKS && AQ_AXIS == 0
#if AQ_BLOCKS_IN
// Pixels x0 - kTaps .. x0 + 1 + kTaps of rows y0 and y0 + 1 (x0 and y0 even): the kTaps + 1
// blocks from (x0 - kTaps) / 2 hold them. Pixels past the image repeat its edge pixels, which
// lie in the edge blocks that the clamped reads return.
void read_block_rows(int x0, int y0, out vec4 texels[2][2 * kTaps + 2]) {
  ivec2 last = u_image_size - 1;
  int b0 = (x0 - kTaps) >> 1;
  uvec4 blocks[kTaps + 1];
  for (int j = 0; j <= kTaps; ++j) {
    blocks[j] = texelFetch(u_blocks, ivec2(clamp(b0 + j, 0, last.x >> 1), y0 >> 1), 0);
  }
  for (int r = 0; r < 2; ++r) {
    int y = min(y0 + r, last.y);
    for (int i = 0; i < 2 * kTaps + 2; ++i) {
      int x = clamp(x0 - kTaps + i, 0, last.x);
      texels[r][i] = aq_hdr8_word_decode(aq_hdr8_block_word(blocks[i >> 1], x & 1, y & 1));
    }
  }
}
#else
// The same from an encoded image of pixels.
void read_block_rows(int x0, int y0, out vec4 texels[2][2 * kTaps + 2]) {
  ivec2 last = textureSize(u_image, 0) - 1;
  for (int r = 0; r < 2; ++r) {
    for (int i = 0; i < 2 * kTaps + 2; ++i) {
      ivec2 p = clamp(ivec2(x0 - kTaps + i, y0 + r), ivec2(0), last);
      texels[r][i] = aq_hdr8_decode(texelFetch(u_image, p, 0));
    }
  }
}
#endif

// Row y of the block's two pixels at x0 and x0 + 1, blurred from `texels`, pixels x0 - kTaps ..
// x0 + 1 + kTaps of the row.
void blur_block_row(int x0, int y, vec4 texels[2 * kTaps + 2], out vec4 left, out vec4 right) {
  vec4 row[2 * kTaps + 1];
  for (int i = 0; i <= 2 * kTaps; ++i) row[i] = texels[i];
  left = blur_row(vec2(float(x0) + 0.5, float(y) + 0.5), row);
  for (int i = 0; i <= 2 * kTaps; ++i) row[i] = texels[i + 1];
  right = blur_row(vec2(float(x0) + 1.5, float(y) + 0.5), row);
}

void main() {
  ivec2 block = ivec2(gl_FragCoord.xy);
  vec4 texels[2][2 * kTaps + 2];
  read_block_rows(2 * block.x, 2 * block.y, texels);
  vec4 c00, c10, c01, c11;
  blur_block_row(2 * block.x, 2 * block.y, texels[0], c00, c10);
  blur_block_row(2 * block.x, 2 * block.y + 1, texels[1], c01, c11);
  o_block = uvec4(aq_hdr8_word_encode(c00), aq_hdr8_word_encode(c10), aq_hdr8_word_encode(c01),
                  aq_hdr8_word_encode(c11));
}
#elif AQ_BLOCKS && AQ_AXIS == 1
void main() {
  ivec2 p = ivec2(gl_FragCoord.xy);
  int last_row = u_image_size.y - 1;
  int last_block = last_row >> 1;
  int column = p.x & 1;
  // Rows p.y - kTaps .. p.y + kTaps lie in the kTaps + 1 blocks from b0, one of whose rows is
  // unused (the last block's second from an even first row, the first block's first from an
  // odd one). Rows past the image repeat its edge rows, which lie in the edge blocks that the
  // clamped reads return.
  int first = p.y - kTaps;
  int b0 = first >> 1;  // floor: the shift extends the sign
  bool odd = (first & 1) != 0;
  uvec4 blocks[kTaps + 1];
  for (int i = 0; i <= kTaps; ++i) {
    blocks[i] = texelFetch(u_blocks, ivec2(p.x >> 1, clamp(b0 + i, 0, last_block)), 0);
  }
  vec4 row[2 * kTaps + 1];
  for (int i = 0; i <= 2 * kTaps; ++i) {
    int source = clamp(first + i, 0, last_row);
    // Block of row first + i: index i >> 1 from an even start, (i + 1) >> 1 from an odd one.
    uvec4 words = odd ? blocks[(i + 1) >> 1] : blocks[i >> 1];
    row[i] = aq_hdr8_word_decode(aq_hdr8_block_word(words, column, source & 1));
  }
  o_color = aq_epilogue(blur_row(gl_FragCoord.xy, row));
#if AQ_ENCODE_HDR8
  o_color = aq_hdr8_encode(o_color);
#endif
}
#else
void main() {
  vec2 frag = gl_FragCoord.xy;
  vec2 inv_size = 1.0 / u_size;
#if AQ_DECODE_HDR8
  ivec2 pixel = ivec2(frag);
  ivec2 axis = ivec2(kAxis);
  ivec2 last = textureSize(u_image, 0) - 1;
  vec4 row[2 * kTaps + 1];
  for (int t = -kTaps; t <= kTaps; ++t) {
    row[kTaps + t] = aq_hdr8_decode(texelFetch(u_image, clamp(pixel + t * axis, ivec2(0), last), 0));
  }
  o_color = blur_row(frag, row);
#else
  float log2_q = log2_ratio(frag);
  vec4 centre = texelFetch(u_image, ivec2(frag), 0);
  vec4 sum = centre;
  float norm = 1.0;
  float first_weight = 0.0;
  for (int k = 1; k <= kPairs; ++k) {
    float i = float(2 * k - 1);
    float ratio = exp2((2.0 * i + 1.0) * log2_q);  // w(2k) / w(2k−1): no 0/0 on underflow
    float offset = i + ratio / (1.0 + ratio);
    float weight = exp2(i * i * log2_q) * (1.0 + ratio);
    sum += weight * (texture(u_image, (frag + offset * kAxis) * inv_size) +
                     texture(u_image, (frag - offset * kAxis) * inv_size));
    norm += 2.0 * weight;
    if (k == 1) first_weight = weight;
  }
  // Every neighbour weight underflowed: the input itself, exactly (no 0 · ∞ from a neighbour).
  o_color = first_weight > 0.0 ? sum / norm : centre;
#endif
#if AQ_AXIS == 1
  o_color = aq_epilogue(o_color);  // the pointwise nodes after the blur, when the host fuses them
#endif
#if AQ_ENCODE_HDR8
  o_color = aq_hdr8_encode(o_color);
#endif
}
#endif
