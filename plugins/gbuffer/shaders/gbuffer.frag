// Writes the six gbuffer targets; albedo is the vertex colour times the base colour texture. Covered pixels get w = 1 in position, normal and albedo and
// their object id (>= 1); the clear values (w = 0, id 0, depth = far plane) mark the background.
#include "aquarelle/gbuffer_surface.glsl"
in vec3 v_world;
in vec3 v_normal;
in vec3 v_color;
in float v_view_depth;
in vec2 v_uv;

layout(location = 0) out vec4 o_position;
layout(location = 1) out vec4 o_normal;
layout(location = 2) out vec4 o_albedo;
layout(location = 3) out float o_depth;
layout(location = 4) out float o_id;
layout(location = 5) out uvec4 o_surface;  // aquarelle/gbuffer_surface.glsl

uniform float u_object_id;
uniform sampler2D u_base_color;  // the mesh's texture, or one white texel
uniform float u_alpha_cutoff;    // texture alpha below it is a hole; 0: opaque

// gbuffer.cpp defines AQ_GBUFFER_TEXTURED 0 for meshes without a base colour texture: no texture
// read and no discard, so llvmpipe can test depth before running the shader (a shader that may
// discard runs for every overdrawn fragment).
#ifndef AQ_GBUFFER_TEXTURED
#define AQ_GBUFFER_TEXTURED 1
#endif

void main() {
#if AQ_GBUFFER_TEXTURED
  vec4 texel = texture(u_base_color, v_uv);
  // Cut-out cards (seaweed, plants): a hole, not a transparent colour (seed 001's discard).
  if (texel.a < u_alpha_cutoff) discard;
#else
  const vec4 texel = vec4(1.0);
#endif
  vec3 n = v_normal;
  if (dot(n, n) > 1e-12) {
    // Thin single-sided parts (fins, seaweed) are seen from both sides: light the visible side.
    n = gl_FrontFacing ? normalize(n) : -normalize(n);
  } else {
    // A zero interpolated normal (opposite vertex normals across a triangle) falls back to the
    // face's own normal, which faces the camera, instead of normalising to NaN.
    n = cross(dFdx(v_world), dFdy(v_world));
    n = dot(n, n) > 0.0 ? normalize(n) : vec3(0.0, 1.0, 0.0);
  }
  o_position = vec4(v_world, 1.0);
  o_normal = vec4(n, 1.0);
  o_albedo = vec4(v_color * texel.rgb, 1.0);
  o_depth = v_view_depth;
  o_id = u_object_id;
  o_surface = aq_surface_pack(o_normal.xyz, o_albedo.rgb, o_id, o_depth);
}
