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
#include "aquarelle/hdr8.glsl"
#ifndef AQ_DECODE_HDR8
#define AQ_DECODE_HDR8 0
#endif
#ifndef AQ_ENCODE_HDR8
#define AQ_ENCODE_HDR8 0
#endif
layout(location = 0) out vec4 o_color;

uniform sampler2D u_image;
uniform float u_sigma;  // σ at strength 1, working pixels

float blur_strength(vec2 frag);

const int kPairs = AQ_RADIUS / 2;
const vec2 kAxis = AQ_AXIS == 0 ? vec2(1.0, 0.0) : vec2(0.0, 1.0);

void main() {
  vec2 frag = gl_FragCoord.xy;
  float sigma = u_sigma * blur_strength(frag);
  // log2 q; σ = 0 makes every weight but the centre's 0 (a select, not a branch).
  float log2_q = sigma > 0.0 ? -0.7213475204444817 / (sigma * sigma) : -1.0e30;
  vec2 inv_size = 1.0 / u_size;
  float norm = 1.0;
  float first_weight = 0.0;
#if AQ_DECODE_HDR8
  ivec2 pixel = ivec2(frag);
  ivec2 axis = ivec2(kAxis);
  ivec2 last = textureSize(u_image, 0) - 1;
  vec4 centre = aq_hdr8_decode(texelFetch(u_image, pixel, 0));
  vec4 sum = centre;
  for (int t = 1; t <= 2 * kPairs; ++t) {
    float weight = exp2(float(t * t) * log2_q);
    vec4 ahead = texelFetch(u_image, clamp(pixel + t * axis, ivec2(0), last), 0);
    vec4 behind = texelFetch(u_image, clamp(pixel - t * axis, ivec2(0), last), 0);
    sum += weight * (aq_hdr8_decode(ahead) + aq_hdr8_decode(behind));
    norm += 2.0 * weight;
    if (t == 1) first_weight = weight;
  }
#else
  vec4 centre = texelFetch(u_image, ivec2(frag), 0);
  vec4 sum = centre;
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
#endif
  // Every neighbour weight underflowed: the input itself, exactly (no 0 · ∞ from a neighbour).
  o_color = first_weight > 0.0 ? sum / norm : centre;
#if AQ_AXIS == 1
  o_color = aq_epilogue(o_color);  // the pointwise nodes after the blur, when the host fuses them
#endif
#if AQ_ENCODE_HDR8
  o_color = aq_hdr8_encode(o_color);
#endif
}
