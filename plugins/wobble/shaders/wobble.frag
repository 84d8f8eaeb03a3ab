// Paper wobble (seed sec. 3.4): each lookup moves by the paper height's gradient times `strength`.
// The gradient is a true derivative: central differences one paper pixel either side, divided
// by the real step (2 paper pixels). The displacement is in paper pixels and converted to uv,
// so it covers the same part of the image at every output resolution. The sampler clamps to
// the edge, so no lookup leaves the image. wobble.cpp defines AQ_WOBBLE_GRADIENT 1 when the
// paper's precomputed gradient is connected.
#ifndef AQ_WOBBLE_GRADIENT
#define AQ_WOBBLE_GRADIENT 0
#endif
// AQ_WOBBLE_DECODE_HDR8 1: u_image holds AQ_FORMAT_RGBA8_HDR. The bilinear blend must mix
// light, not codes (the encoding is not linear), so the four texels are fetched, decoded and
// mixed here with the weights and clamp-to-edge of the hardware's filter.
#ifndef AQ_WOBBLE_DECODE_HDR8
#define AQ_WOBBLE_DECODE_HDR8 0
#endif
// AQ_WOBBLE_ENCODE_HDR8 1: the target is AQ_FORMAT_RGBA8_HDR; what is written (after the
// epilogue) is encoded.
#ifndef AQ_WOBBLE_ENCODE_HDR8
#define AQ_WOBBLE_ENCODE_HDR8 0
#endif
#ifndef AQ_WOBBLE_BLOCKS
#define AQ_WOBBLE_BLOCKS 0
#endif
// AQ_WOBBLE_OUT_BLOCKS 1: the target is AQ_FORMAT_RGBA8_HDR_BLOCKS (its reader, the blur, reads
// 2 x 2 blocks): a fragment per block writes its four pixels, each wobbled, passed through the
// epilogue at its own centre and encoded: the bytes four fragments would write to an encoded
// image.
#ifndef AQ_WOBBLE_OUT_BLOCKS
#define AQ_WOBBLE_OUT_BLOCKS 0
#endif
#include "aquarelle/hdr8.glsl"
#if AQ_WOBBLE_OUT_BLOCKS
layout(location = 0) out uvec4 o_block;  // pixels (0, 0), (1, 0), (0, 1), (1, 1) of the block
#else
layout(location = 0) out vec4 o_color;
#endif
uniform vec2 u_out_size;  // the output's size in pixels

#if AQ_WOBBLE_BLOCKS
// The image in 2 x 2 blocks of packed encoded pixels (AQ_FORMAT_RGBA8_HDR_BLOCKS, plugin.h).
uniform usampler2D u_blocks;
uniform ivec2 u_image_size;
#else
uniform sampler2D u_image;
#endif
uniform sampler2D u_paper;  // height in .r, stretched over the image
uniform vec2 u_paper_size;  // paper pixels across the image
uniform float u_strength;   // paper pixels of displacement per unit slope (height per paper pixel)

float paper_height(vec2 uv) { return texture(u_paper, uv).r; }

#if AQ_WOBBLE_BLOCKS || AQ_WOBBLE_DECODE_HDR8
// Texel p (inside the image) of an encoded image, decoded.
vec4 decoded_texel(ivec2 p) {
#if AQ_WOBBLE_BLOCKS
  return aq_hdr8_block_pixel(u_blocks, p);
#else
  return aq_hdr8_decode(texelFetch(u_image, p, 0));
#endif
}
#endif

vec4 image_at(vec2 uv) {
#if AQ_WOBBLE_BLOCKS || AQ_WOBBLE_DECODE_HDR8
#if AQ_WOBBLE_BLOCKS
  ivec2 last = u_image_size - 1;
#else
  ivec2 last = textureSize(u_image, 0) - 1;
#endif
  vec2 t = uv * vec2(last + 1) - 0.5;
  vec2 f = fract(t);
  ivec2 i0 = ivec2(floor(t));
  vec4 c00 = decoded_texel(clamp(i0, ivec2(0), last));
  vec4 c10 = decoded_texel(clamp(i0 + ivec2(1, 0), ivec2(0), last));
  vec4 c01 = decoded_texel(clamp(i0 + ivec2(0, 1), ivec2(0), last));
  vec4 c11 = decoded_texel(clamp(i0 + ivec2(1, 1), ivec2(0), last));
  return mix(mix(c00, c10, f.x), mix(c01, c11, f.x), f.y);
#else
  return texture(u_image, uv);
#endif
}

// The image wobbled at `uv`, the centre of an output pixel.
vec4 wobbled(vec2 uv) {
  vec2 step_uv = 1.0 / u_paper_size;
#if AQ_WOBBLE_GRADIENT
  // u_paper holds the paper's precomputed gradient (paper_gradient.frag): one read.
  vec2 gradient = texture(u_paper, uv).rg;
#else
  vec2 gradient = vec2(paper_height(uv + vec2(step_uv.x, 0.0)) -
                           paper_height(uv - vec2(step_uv.x, 0.0)),
                       paper_height(uv + vec2(0.0, step_uv.y)) -
                           paper_height(uv - vec2(0.0, step_uv.y))) /
                  2.0;
#endif
  // A NaN or infinite paper would throw the lookup anywhere: keep the pixel in place instead.
  if (any(isnan(gradient)) || any(isinf(gradient))) gradient = vec2(0.0);
  // A paper's heights lie in [0, 1], so its slope per paper pixel is at most 1 (0.5 for the
  // central difference): the clamp only bounds a foreign image's, and with it how far a lookup
  // moves, which is what a change of the image can reach (wobble.cpp, damage tracking).
  gradient = clamp(gradient, vec2(-1.0), vec2(1.0));
  return image_at(uv + u_strength * gradient * step_uv);
}

// aq_epilogue: the pointwise nodes after the wobble (edge) when the host fuses them.
void main() {
#if AQ_WOBBLE_OUT_BLOCKS
  ivec2 block = ivec2(gl_FragCoord.xy);
  uint words[4];
  for (int i = 0; i < 4; ++i) {
    vec2 pixel = vec2(2 * block + ivec2(i & 1, i >> 1)) + 0.5;
    words[i] = aq_hdr8_word_encode(aq_epilogue_at(wobbled(pixel / u_out_size), pixel));
  }
  o_block = uvec4(words[0], words[1], words[2], words[3]);
#else
  o_color = aq_epilogue(wobbled(gl_FragCoord.xy / u_out_size));
#if AQ_WOBBLE_ENCODE_HDR8
  o_color = aq_hdr8_encode(o_color);
#endif
#endif
}
