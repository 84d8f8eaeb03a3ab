// Linear HDR colour in an RGBA8 texture (AQ_FORMAT_RGBA8_HDR, plugin.h):
// `#include "aquarelle/hdr8.glsl"`.
//
// rgb is stored per channel as e = sqrt(c / (1 + c)), c >= 0; alpha is linear in [0, 1]. The
// map is monotone, so min, max and comparisons of whole channels work on the stored values
// (erode and dilate never decode). c / (1 + c) reaches every HDR value (c = 6 under the
// caustics is e = 0.93); the square root spends the 256 codes evenly in relative terms.
// Rounding e to 8 bits moves it by at most 1/510, and dc/de = 2e (1 + c)^2, so
//   |decode(encode(c)) - c| <= e (1 + c)^2 / 255,  relative (1 + c)^1.5 / (255 sqrt(c)):
// 1.1 % at c = 1, 1.4 % at c = 0.1 and c = 2, 0.011 absolute at c = 1 (sRGB's 8 bits: 0.2 %
// at 1). Why 8 bits at all: llvmpipe reads RGBA8 texels through a path of its own, about
// three times as fast as float ones when a pass reads several (docs/performance.md).

vec4 aq_hdr8_encode(vec4 c) {
  vec3 rgb = max(c.rgb, vec3(0.0));  // negative light is not light; NaN becomes 0
  return vec4(sqrt(rgb / (vec3(1.0) + rgb)), clamp(c.a, 0.0, 1.0));
}

vec4 aq_hdr8_decode(vec4 e) {
  vec3 y = e.rgb * e.rgb;
  // e = 1 (code 255) stands for everything above 254.5/255: decode it as 1 / (1 - y) = 256-ish.
  return vec4(y / max(vec3(1.0) - y, vec3(1.0 / 256.0)), e.a);
}

// A pixel's word of an AQ_FORMAT_RGBA8_HDR_BLOCKS texture, decoded, and pixel p (inside the
// image) of such a texture (plugin.h: the words of pixels (0, 0), (1, 0), (0, 1), (1, 1) of
// each 2 x 2 block in x, y, z, w), decoded. The bytes are scaled by 1/255 rather than unpacked
// with unpackUnorm4x8 (a division): llvmpipe's RGBA8 texel fetch converts so, and a last-bit
// difference can round a re-encoded result to the next code.
vec4 aq_hdr8_word_decode(uint word) {
  vec4 bytes = vec4(uvec4(word, word >> 8, word >> 16, word >> 24) & 0xFFu);
  return aq_hdr8_decode(bytes * (1.0 / 255.0));
}

// The word an RGBA8 target stores for colour c encoded: a pixel of a block.
uint aq_hdr8_word_encode(vec4 c) { return packUnorm4x8(aq_hdr8_encode(c)); }

// Word of a block's pixel in column `column` (0 or 1) and row `row` (0 or 1).
uint aq_hdr8_block_word(uvec4 words, int column, int row) {
  uvec2 pair = row == 0 ? words.xy : words.zw;
  return column == 0 ? pair.x : pair.y;
}

vec4 aq_hdr8_block_pixel(usampler2D blocks, ivec2 p) {
  uvec4 words = texelFetch(blocks, p >> 1, 0);
  return aq_hdr8_word_decode(aq_hdr8_block_word(words, p.x & 1, p.y & 1));
}
