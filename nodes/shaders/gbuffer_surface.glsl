// The g-buffer's `surface` target (AQ_FORMAT_RGBA32UI): what a deferred light reads of a
// pixel besides its position, in one texel: `#include "aquarelle/gbuffer_surface.glsl"`.
//
//   x = packHalf2x16(normal.xy)
//   y = packHalf2x16(normal.z, albedo.r)
//   z = packHalf2x16(albedo.gb)
//   w = floatBitsToUint(id)          (the object id as the id target's float, 0 = background)
//
// Normal and albedo are the float values rounded to the nearest half (packHalf2x16), in every
// precision: a light reading `surface` sees exactly the g-buffer's float targets rounded so
// (tests/plugins/gbuffer_surface_test.cpp). That is not always what the RGBA16F targets hold at
// half precision: llvmpipe rounds those towards zero, so `surface` is the closer of the two.
// Why pack: on llvmpipe a read is the cost of a pass, and one 16-byte texel costs less than
// three texels of three textures (docs/performance.md, the lever row "gbuffer: normal, albedo
// and id in one packed surface texel for the light").

uvec4 aq_surface_pack(vec3 normal, vec3 albedo, float id) {
  return uvec4(packHalf2x16(normal.xy), packHalf2x16(vec2(normal.z, albedo.r)),
               packHalf2x16(albedo.gb), floatBitsToUint(id));
}

struct aq_surface {
  vec3 normal;
  vec3 albedo;
  float id;
};

aq_surface aq_surface_unpack(uvec4 words) {
  vec2 normal_xy = unpackHalf2x16(words.x);
  vec2 normal_z_albedo_r = unpackHalf2x16(words.y);
  vec2 albedo_gb = unpackHalf2x16(words.z);
  return aq_surface(vec3(normal_xy, normal_z_albedo_r.x),
                    vec3(normal_z_albedo_r.y, albedo_gb), uintBitsToFloat(words.w));
}
