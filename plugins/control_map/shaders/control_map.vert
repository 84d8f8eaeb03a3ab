// Scene vertices to clip space for the control map; object-space and world positions, the world
// normal and the uv go to the fragment shader (same transform as the gbuffer's, so the pixels
// line up with it).
layout(location = 0) in vec3 a_position;
layout(location = 1) in vec3 a_normal;
layout(location = 3) in vec2 a_uv;

uniform mat4 u_model;
uniform mat3 u_normal_matrix;
uniform mat4 u_view;
uniform mat4 u_projection;

out vec3 v_object;
out vec3 v_world;
out vec3 v_normal;
out vec2 v_uv;

// The depth pre-pass and the colour pass must land on the same depths (EQUAL test).
invariant gl_Position;

void main() {
  vec4 world = u_model * vec4(a_position, 1.0);
  v_object = a_position;
  v_world = world.xyz;
  v_normal = u_normal_matrix * a_normal;
  v_uv = a_uv;
  gl_Position = u_projection * (u_view * world);
}
