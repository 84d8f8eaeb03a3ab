// Integer division without the integer divide: `#include "aquarelle/integer_division.glsl"`;
// guarded, so two stages of one fused shader may both include it.
//   aq_floor_divide(n, d)        = floor(n / d) for any n and d >= 1 (int or ivec2)
//   aq_scaled_texel(p, from, to) = p · to / from: the texel of an image of size `to` under texel
//                                  p >= 0 of an image of size `from` (the nearest, proportional
//                                  mapping every node uses when its inputs differ in size)
//
// Why: x86 has no vector integer division, so llvmpipe divides lane by lane. One ivec2 division
// cost about 4 ms of a 1280x720 pass (paper_relief in waterfall.json, docs/performance.md, issue
// 35), more than the rest of the pixel's work, and the caustics' coverage pass was dominated by
// them. The quotient comes from a float division and is corrected to the exact one: for |n| below
// 2^31 and quotients up to 16384 the float estimate is within 0.01 of n / d, so its floor is the
// exact quotient or one off, and the remainder's sign or size says which way (below 2^24, as for
// every texture up to 4096 x 4096, the estimate is already exact).
#ifndef AQ_INTEGER_DIVISION_GLSL
#define AQ_INTEGER_DIVISION_GLSL

int aq_floor_divide(int n, int d) {
  int q = int(floor(float(n) / float(d)));
  int r = n - q * d;  // the remainder of the estimate: in [0, d) when it is exact
  return q - (r < 0 ? 1 : 0) + (r >= d ? 1 : 0);
}

ivec2 aq_floor_divide(ivec2 n, ivec2 d) {
  ivec2 q = ivec2(floor(vec2(n) / vec2(d)));
  ivec2 r = n - q * d;
  return q - ivec2(lessThan(r, ivec2(0))) + ivec2(greaterThanEqual(r, d));
}

ivec2 aq_scaled_texel(ivec2 p, ivec2 from, ivec2 to) { return aq_floor_divide(p * to, from); }

#endif  // AQ_INTEGER_DIVISION_GLSL
