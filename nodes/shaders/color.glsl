// Shared colour helpers for plugin shaders: `#include "aquarelle/color.glsl"`.
// HSV after Smith (1978) with V = max(r,g,b); defined for every finite input, including grey
// (S = 0, H = 0), black, and values above 1 (V > 1 is kept, not clamped).

vec3 aq_rgb_to_hsv(vec3 c) {
  float v = max(c.r, max(c.g, c.b));
  float m = min(c.r, min(c.g, c.b));
  float d = v - m;
  float s = v > 0.0 ? d / v : 0.0;
  float h = 0.0;
  if (d > 0.0) {
    if (v == c.r) {
      h = (c.g - c.b) / d;
    } else if (v == c.g) {
      h = 2.0 + (c.b - c.r) / d;
    } else {
      h = 4.0 + (c.r - c.g) / d;
    }
    h = fract(h / 6.0);
  }
  return vec3(h, s, v);
}

vec3 aq_hsv_to_rgb(vec3 hsv) {
  float h = fract(hsv.x) * 6.0;
  float s = hsv.y;
  float v = hsv.z;
  vec3 k = clamp(abs(mod(h + vec3(0.0, 4.0, 2.0), 6.0) - 3.0) - 1.0, 0.0, 1.0);
  return v * mix(vec3(1.0), k, s);
}

float aq_luminance(vec3 c) { return dot(c, vec3(0.2126, 0.7152, 0.0722)); }
