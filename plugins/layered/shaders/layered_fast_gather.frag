// One axis of a separable gather over the short lists of the `fast` method
// (layered_lists.glsl), nearest taps first, clamped to the image:
//   AQ_GATHER 0: Gaussian of intensity, diffuse and depth; the list grows with the neighbours'
//                layers (the four nearest are kept)
//   AQ_GATHER 1: Gaussian of one value per layer of a fixed list (the wet edges)
//   AQ_GATHER 2: maximum of one value per layer of a fixed list (thin shapes' peaks)
layout(location = 0) out vec4 o_first;
#if AQ_GATHER == 0
layout(location = 1) out vec4 o_intensity;
layout(location = 2) out vec4 o_diffuse;
layout(location = 3) out vec4 o_depth;
uniform sampler2D u_intensity;
uniform sampler2D u_diffuse;
uniform sampler2D u_depth;
#endif
uniform sampler2D u_keys;    // the lists' keys (for AQ_GATHER 1 and 2: of the fixed lists)
uniform sampler2D u_values;  // AQ_GATHER 1 and 2: one value per key
uniform ivec2 u_axis;
#ifdef AQ_RADIUS
// The radius compiled in (fast_layers.cpp does for small radii): llvmpipe then unrolls the taps
// and reads each weight at a constant index instead of one lane at a time.
const int kRadius = AQ_RADIUS;
#else
uniform int u_radius;
#define kRadius u_radius
#endif
uniform float u_weights[64];  // Gaussian weights by distance (AQ_GATHER 0 and 1)

void main() {
  ivec2 p = ivec2(gl_FragCoord.xy);
  ivec2 size = textureSize(u_keys, 0);
#if AQ_GATHER == 0
  vec4 keys = vec4(0.0), intensity = vec4(0.0), diffuse = vec4(0.0), depth = vec4(0.0);
#else
  vec4 keys = texelFetch(u_keys, p, 0);
  vec4 acc = vec4(0.0);
#endif
  for (int n = 0; n <= 2 * kRadius; ++n) {
    int offset = (n + 1) / 2 * (n % 2 == 1 ? 1 : -1);  // 0, 1, -1, 2, -2, ...
    ivec2 q = list_clamp(p + offset * u_axis, size);
    vec4 tap_keys = texelFetch(u_keys, q, 0);
#if AQ_GATHER == 0
    mat4 m = list_merge(keys, tap_keys);
    float w = u_weights[abs(offset)];
    intensity += w * (m * texelFetch(u_intensity, q, 0));
    diffuse += w * (m * texelFetch(u_diffuse, q, 0));
    depth += w * (m * texelFetch(u_depth, q, 0));
#elif AQ_GATHER == 1
    acc += u_weights[abs(offset)] * (list_match(keys, tap_keys) * texelFetch(u_values, q, 0));
#else
    acc = max(acc, list_match(keys, tap_keys) * texelFetch(u_values, q, 0));
#endif
  }
#if AQ_GATHER == 0
  o_first = keys;
  o_intensity = intensity;
  o_diffuse = diffuse;
  o_depth = depth;
#else
  o_first = acc;
#endif
}
