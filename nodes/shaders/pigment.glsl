// Shared subtractive colour mixing for plugin shaders: `#include "aquarelle/pigment.glsl"`.
// Pure functions (no uniforms). reference/pigment_mix.h implements the same maths in
// double; the maths and its sources are in plugins/pigment_mix/README.md.
//
//   aq_mix_rgb(a, b, t)   additive lerp, for comparison
//   aq_mix_cmyk(a, b, t)  the seed's (004) lerp in CMYK: rgb -> cmyk, lerp, back
//   aq_mix_km(a, b, t)    Kubelka–Munk two-constant mixing (Curtis et al. 1997): each colour is
//                         a pigment whose unit-thickness layer looks like it over white paper
//                         and AQ_KM_BLACK_RATIO times as bright over black; K and S of both are
//                         mixed by concentration, the mixture is laid at unit thickness on white
//   aq_km_glaze(under, colour, thickness)  a layer of the pigment `colour` of `thickness`
//                         over a background `under` (Curtis's composite of two layers)
// Inputs are clamped to [0, 1] and NaN counts as 0, so every result is finite.

#define AQ_KM_BLACK_RATIO 0.2
#define AQ_KM_EPS 1.0e-4

vec3 aq_pigment_sanitize(vec3 c) {
  // NaN fails every comparison: clamp() of NaN is undefined, so pick it out first.
  return vec3(c.r >= 0.0 ? min(c.r, 1.0) : 0.0, c.g >= 0.0 ? min(c.g, 1.0) : 0.0,
              c.b >= 0.0 ? min(c.b, 1.0) : 0.0);
}

vec3 aq_mix_rgb(vec3 a, vec3 b, float t) {
  return mix(aq_pigment_sanitize(a), aq_pigment_sanitize(b), t);
}

vec4 aq_rgb_to_cmyk(vec3 c) {
  float k = 1.0 - max(c.r, max(c.g, c.b));
  float d = 1.0 - k;  // = max channel; 0 for black, whose c, m, y are set to 0
  vec3 cmy = d > 0.0 ? (vec3(1.0) - c - vec3(k)) / d : vec3(0.0);
  return vec4(cmy, k);
}

vec3 aq_cmyk_to_rgb(vec4 cmyk) {
  return (vec3(1.0) - cmyk.xyz) * (1.0 - cmyk.w);
}

vec3 aq_mix_cmyk(vec3 a, vec3 b, float t) {
  return aq_cmyk_to_rgb(mix(aq_rgb_to_cmyk(aq_pigment_sanitize(a)),
                            aq_rgb_to_cmyk(aq_pigment_sanitize(b)), t));
}

// ---- Kubelka–Munk --------------------------------------------------------------------------

float aq_acoth(float x) { return 0.5 * log((x + 1.0) / (x - 1.0)); }

// Curtis et al. 1997, sec. 4.3: absorption K and scattering S (per unit thickness) of a pigment
// whose unit layer reflects rw over white and rb over black (0 < rb < rw < 1):
//   a = ½ (rw + (rb − rw + 1) / rb),  b = √(a² − 1),
//   S = arccoth((b² − (a − rw)(a − 1)) / (b (1 − rw))) / b,  K = S (a − 1).
// Written without cancellation (same values): a − 1 = (1 − rw)(1 − rb) / (2 rb),
// b² = (a − 1)(a + 1) and b² − (a − rw)(a − 1) = (a − 1)(1 + rw), so the arccoth argument is
// (1 − rb)(1 + rw) / (2 rb b).
vec2 aq_km_ks(float rw, float rb) {
  rw = clamp(rw, 2.0 * AQ_KM_EPS, 1.0 - AQ_KM_EPS);
  rb = clamp(rb, AQ_KM_EPS, rw - AQ_KM_EPS);
  float am1 = (1.0 - rw) * (1.0 - rb) / (2.0 * rb);
  float b = sqrt(am1 * (am1 + 2.0));
  float arg = (1.0 - rb) * (1.0 + rw) / (2.0 * rb * b);
  float s = aq_acoth(max(arg, 1.0 + 1.0e-6)) / b;
  return vec2(am1 * s, s);  // (K, S)
}

// Reflectance and transmittance of a layer of thickness x: a = 1 + K/S, b = √(a² − 1),
// c = a sinh(bSx) + b cosh(bSx), R = sinh(bSx) / c, T = b / c.
vec2 aq_km_layer(float k, float s, float x) {
  if (!(s > 0.0) || !(x > 0.0)) return vec2(0.0, 1.0);
  float q = k / s;
  float a = 1.0 + q;
  float b = sqrt(max(q * (q + 2.0), 1.0e-12));
  float bsx = min(b * s * x, 40.0);  // beyond, the layer is opaque to float precision
  float c = a * sinh(bsx) + b * cosh(bsx);
  return vec2(sinh(bsx) / c, b / c);
}

// Layer (R1, T1) over a background reflecting r2: R = R1 + T1² r2 / (1 − R1 r2).
float aq_km_over(vec2 layer, float r2) {
  return layer.x + layer.y * layer.y * r2 / (1.0 - layer.x * r2);
}

vec3 aq_mix_km(vec3 a, vec3 b, float t) {
  a = aq_pigment_sanitize(a);
  b = aq_pigment_sanitize(b);
  vec3 result;
  for (int i = 0; i < 3; ++i) {
    vec2 ka = aq_km_ks(a[i], AQ_KM_BLACK_RATIO * a[i]);
    vec2 kb = aq_km_ks(b[i], AQ_KM_BLACK_RATIO * b[i]);
    vec2 ks = mix(ka, kb, t);
    result[i] = aq_km_over(aq_km_layer(ks.x, ks.y, 1.0), 1.0);
  }
  return aq_pigment_sanitize(result);
}

// A glaze: `thickness` units of the pigment that looks like `colour` at unit thickness on white,
// over the background `under`.
vec3 aq_km_glaze(vec3 under, vec3 colour, float thickness) {
  under = aq_pigment_sanitize(under);
  colour = aq_pigment_sanitize(colour);
  vec3 result;
  for (int i = 0; i < 3; ++i) {
    vec2 ks = aq_km_ks(colour[i], AQ_KM_BLACK_RATIO * colour[i]);
    result[i] = aq_km_over(aq_km_layer(ks.x, ks.y, thickness), under[i]);
  }
  return aq_pigment_sanitize(result);
}
