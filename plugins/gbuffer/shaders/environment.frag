// The environment seen behind the scene, written into the albedo target before the meshes:
// a vertical gradient by the direction of each pixel's view ray, from `bottom` (looking
// straight down) to `top` (straight up), mixed by (1 + dir.y) / 2. Alpha stays 0: the pixel
// is still background (id 0) for every later pass; cel_light shows it when asked. The other
// targets get the values that mark the background (what the clears write without an
// environment), so this one pass replaces five clears.
#include "aquarelle/gbuffer_surface.glsl"
in vec2 v_uv;

layout(location = 0) out vec4 o_position;
layout(location = 1) out vec4 o_normal;
layout(location = 2) out vec4 o_albedo;
layout(location = 3) out float o_depth;
layout(location = 4) out float o_id;
layout(location = 5) out uvec4 o_surface;

uniform mat4 u_inverse_view_projection;
uniform vec3 u_top;
uniform vec3 u_bottom;
uniform float u_far_plane;

void main() {
  vec2 ndc = v_uv * 2.0 - 1.0;
  vec4 near_point = u_inverse_view_projection * vec4(ndc, -1.0, 1.0);
  vec4 far_point = u_inverse_view_projection * vec4(ndc, 1.0, 1.0);
  vec3 direction = normalize(far_point.xyz / far_point.w - near_point.xyz / near_point.w);
  o_albedo = vec4(mix(u_bottom, u_top, 0.5 + 0.5 * direction.y), 0.0);
  o_position = vec4(0.0);
  o_normal = vec4(0.0);
  o_depth = u_far_plane;
  o_id = 0.0;
  o_surface = aq_surface_pack(vec3(0.0), o_albedo.rgb, 0.0, o_depth);
}
