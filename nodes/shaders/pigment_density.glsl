// Pigment density (Bousseau, Kaplan, Thollot & Sillion 2006; seed 000 §3.6), shared by the
// `pigment` and `pigment_apply` nodes: `#include "aquarelle/pigment_density.glsl"`.
//
//   aq_pigment_density(c, weight, n):  C' = C (1 − (1 − C)(d − 1)),  d = clamp(1 + weight·n, 0, 2)
//                                      (for C ≤ 1; above 1 the excess over 1 is kept unchanged)
//
// n is the density texture centred on 0. d ∈ [0, 2] is exactly the condition for [0, 1] to map
// into [0, 1] (plugins/pigment/README.md); d = 1 leaves C unchanged exactly. A NaN or infinite n
// changes nothing. Guarded, so that two stages of one fused shader may both include it.
#ifndef AQ_PIGMENT_DENSITY_GLSL
#define AQ_PIGMENT_DENSITY_GLSL

// Above 1 (an HDR highlight) only the part up to 1 is modified and the excess is kept: the
// formula itself goes negative for c > 1 and d < 1 - 1/(c - 1) (a caustic highlight of 3 under a
// light density of 0.4 turned -0.6), and it is continuous at c = 1 (1 stays 1).
vec3 aq_pigment_density(vec3 c, float weight, float n) {
  if (!(abs(n) <= 1e30)) n = 0.0;
  float d = clamp(1.0 + weight * n, 0.0, 2.0);
  vec3 low = min(c, vec3(1.0));
  return low * (1.0 - (1.0 - low) * (d - 1.0)) + (c - low);
}

#endif  // AQ_PIGMENT_DENSITY_GLSL
