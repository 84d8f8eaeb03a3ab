// The g-buffer's `surface` target (AQ_FORMAT_RGBA32UI): all a deferred light reads of a pixel,
// in one texel: `#include "aquarelle/gbuffer_surface.glsl"`.
//
//   x = packSnorm2x16(octahedral(normal))    the unit normal in 2 x 16 bits
//   y = packHalf2x16(albedo.rg)
//   z = packHalf2x16(albedo.b) | id << 16     the object id as 16 bits (0 = background)
//   w = floatBitsToUint(depth)                the linear view depth, as the depth target's float
//
// The albedo is the float value rounded to the nearest half (packHalf2x16) in every precision.
// The normal is octahedral (Meyer et al. 2010, "On floating-point normal vectors"): the unit
// sphere folded onto the square |u| + |v| <= 1, each coordinate in 16 bits. The decoded normal
// is within 5e-5 rad of the float one, closer than the three halves of a half-precision normal
// target (up to 5e-4); tests/plugins/gbuffer_surface_test.cpp measures both. The depth is
// exact, so a light rebuilds the world position on the camera's ray through the pixel (one
// texel read instead of two: on llvmpipe each read of a full-size texture costs about as much
// as a copy pass's third, docs/performance.md, issue 37's eleventh session). Ids above 65535
// are stored as 65535.

// The octahedral square of a unit vector (0 stays 0): u, v in [-1, 1].
vec2 aq_octahedral_encode(vec3 n) {
  float l1 = abs(n.x) + abs(n.y) + abs(n.z);
  vec2 p = l1 > 0.0 ? n.xy / l1 : vec2(0.0);
  if (n.z < 0.0) {
    // The lower half folds over the square's diagonals.
    vec2 signs = vec2(p.x >= 0.0 ? 1.0 : -1.0, p.y >= 0.0 ? 1.0 : -1.0);
    p = (vec2(1.0) - abs(p.yx)) * signs;
  }
  return p;
}

// The unit vector of a point of the octahedral square.
vec3 aq_octahedral_decode(vec2 p) {
  vec3 n = vec3(p, 1.0 - abs(p.x) - abs(p.y));
  if (n.z < 0.0) {
    vec2 signs = vec2(n.x >= 0.0 ? 1.0 : -1.0, n.y >= 0.0 ? 1.0 : -1.0);
    n.xy = (vec2(1.0) - abs(n.yx)) * signs;
  }
  return normalize(n);
}

uvec4 aq_surface_pack(vec3 normal, vec3 albedo, float id, float depth) {
  uint id16 = uint(clamp(id, 0.0, 65535.0));
  return uvec4(packSnorm2x16(aq_octahedral_encode(normal)), packHalf2x16(albedo.rg),
               (packHalf2x16(vec2(albedo.b, 0.0)) & 0xFFFFu) | (id16 << 16),
               floatBitsToUint(depth));
}

struct aq_surface {
  vec3 normal;
  vec3 albedo;
  float id;
  float depth;
};

aq_surface aq_surface_unpack(uvec4 words) {
  return aq_surface(aq_octahedral_decode(unpackSnorm2x16(words.x)),
                    vec3(unpackHalf2x16(words.y), unpackHalf2x16(words.z).x),
                    float(words.z >> 16), uintBitsToFloat(words.w));
}
