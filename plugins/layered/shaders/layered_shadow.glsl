// Soft shadows by the blurred depth test (seed 003's last step; README "Soft shadows"): per
// receiver pixel the binary visibility V of its gbuffer position in the shadow map and how far
// it lies behind the occluder along the light (gap, scene units), stored as the intermediary
//   r = R · (1 − V) · smoothstep(0, shadow_band, gap)      shadow before the blur
//   g = R                                                   receivers (id ≥ 1)
// blurred next (shared Gaussian) and glazed as its own translucent layer by the composite.
// layered_shadow.frag stores it per pixel (exact method); layered_fast_shadow.frag averages it
// over the low-resolution texels of the fast method.

uniform sampler2D u_id;
uniform sampler2D u_position;  // world position, w = 1 on geometry
uniform sampler2D u_shadow;    // light-space depth (shadowmap.depth), 1 where nothing
uniform mat4 u_light_view_projection;
uniform float u_depth_per_unit;  // shadow-map depth per scene unit along the light
uniform float u_shadow_band;

// (r, g) above at pixel p.
vec2 layered_shadow_at(ivec2 p) {
  float id = texelFetch(u_id, p, 0).r;
  bool receiver = id >= 1.0 && id < 16777216.0 && floor(id) == id;
  vec4 position = texelFetch(u_position, p, 0);
  if (!receiver || any(isnan(position.xyz)) || any(isinf(position.xyz))) {
    return vec2(0.0, receiver ? 1.0 : 0.0);
  }
  vec4 clip = u_light_view_projection * vec4(position.xyz, 1.0);
  vec3 w = clip.xyz / clip.w * 0.5 + 0.5;
  float shadowed = 0.0;
  if (all(greaterThanEqual(w.xy, vec2(0.0))) && all(lessThanEqual(w.xy, vec2(1.0))) && w.z <= 1.0) {
    vec2 size = vec2(textureSize(u_shadow, 0));
    ivec2 texel = ivec2(clamp(floor(w.xy * size), vec2(0.0), size - 1.0));
    float occluder = texelFetch(u_shadow, texel, 0).r;
    if (w.z > occluder) {  // binary visibility: behind the nearest surface the light sees
      float gap = (w.z - occluder) / max(u_depth_per_unit, 1.0e-12);
      shadowed = smoothstep(0.0, max(u_shadow_band, 1.0e-6), gap);
    }
  }
  return vec2(shadowed, 1.0);
}
