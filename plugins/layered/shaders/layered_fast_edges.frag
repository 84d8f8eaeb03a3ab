// Wet-edge detection of the `fast` method at the lists' resolution, pre-filtered (README "Fast
// method"): per listed layer, the exact method's band (the 3x3 Laplacian of the abstracted
// coverage, thresholded by a smooth step from edge_threshold to twice it) evaluated at each of
// the texel's D x D pixels and averaged. The blurred mask at a pixel is the bilinear
// interpolation of the texels around it, as the composite takes it for the abstraction, so the
// band lies where the composite's shape has its edge and moves with it by fractions of a texel:
// blurred and enlarged bilinearly it follows the contour smoothly (a band detected per texel
// has steps D pixels long: a blocky feather).
layout(location = 0) out vec4 o_edges;

uniform sampler2D u_keys;     // the blurred lists' keys
uniform sampler2D u_blurred;  // their blurred intensities
uniform float u_edge_threshold;

const int kGrid = AQ_DIVISOR + 2;  // the texel's pixels and their neighbours, per axis

// A texel's blurred intensities for the keys `keys` (0 for a layer it lacks).
vec4 matched(ivec2 q, ivec2 size, vec4 keys) {
  q = list_clamp(q, size);
  return list_match(keys, texelFetch(u_keys, q, 0)) * texelFetch(u_blurred, q, 0);
}

void main() {
  ivec2 p = ivec2(gl_FragCoord.xy);
  ivec2 size = textureSize(u_keys, 0);
  vec4 keys = texelFetch(u_keys, p, 0);
  vec4 present = vec4(greaterThan(keys, vec4(0.5)));
  vec4 nb[9];  // the 3 x 3 texels around p, row-major from the bottom-left
  vec4 low = vec4(1.0e30), high = vec4(-1.0e30);
  for (int j = 0; j < 3; ++j) {
    for (int i = 0; i < 3; ++i) {
      nb[3 * j + i] = matched(p + ivec2(i - 1, j - 1), size, keys);
      low = min(low, nb[3 * j + i]);
      high = max(high, nb[3 * j + i]);
    }
  }
  float t = layered_threshold(float(AQ_DIVISOR) * gl_FragCoord.xy);  // the texel's centre, in pixels
  float s = max(u_softness, 1.0e-4);
  // Bilinear values lie between the texels': the coverage changes here only if t ± s lies
  // between their lowest and highest.
  bool near = any(greaterThan(present * vec4(lessThan(low, vec4(t + s))) *
                                  vec4(greaterThan(high, vec4(t - s))),
                              vec4(0.0)));
  vec4 sum = vec4(0.0);
  // A loop whose condition is per texel: llvmpipe skips it where no texel of the group needs it.
  for (int once = 0; once < 1 && near; ++once) {
    vec4 a[kGrid * kGrid];
    for (int j = 0; j < kGrid; ++j) {
      for (int i = 0; i < kGrid; ++i) {
        // The pixel's offset from the texel's centre, in texels (|u| < 1).
        vec2 u = (vec2(i, j) + 0.5 - 0.5 * float(kGrid)) / float(AQ_DIVISOR);
        ivec2 c = ivec2(floor(u)) + 1;  // the bottom-left texel of the four, in nb
        vec2 f = fract(u);
        vec4 bottom = mix(nb[3 * c.y + c.x], nb[3 * c.y + c.x + 1], f.x);
        vec4 top = mix(nb[3 * (c.y + 1) + c.x], nb[3 * (c.y + 1) + c.x + 1], f.x);
        a[kGrid * j + i] = layered_abstract(mix(bottom, top, f.y), t);
      }
    }
    float th = max(u_edge_threshold, 1.0e-6);
    for (int j = 1; j <= AQ_DIVISOR; ++j) {
      for (int i = 1; i <= AQ_DIVISOR; ++i) {
        vec4 n[9];
        for (int l = 0; l < 3; ++l) {
          for (int k = 0; k < 3; ++k) n[3 * l + k] = a[kGrid * (j + l - 1) + i + k - 1];
        }
        sum += smoothstep(vec4(th), vec4(2.0 * th), aq_laplacian3x3(n));
      }
    }
  }
  o_edges = present * sum / float(AQ_DIVISOR * AQ_DIVISOR);
}
