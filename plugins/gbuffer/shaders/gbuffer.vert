// Scene vertices to clip space for the gbuffer; world position, normal, colour, uv and linear
// view depth go to the fragment shader.
layout(location = 0) in vec3 a_position;
layout(location = 1) in vec3 a_normal;
layout(location = 2) in vec3 a_color;
layout(location = 3) in vec2 a_uv;  // base colour texture coordinates (0 when untextured)

uniform mat4 u_model;
uniform mat3 u_normal_matrix;  // inverse transpose of the model's upper 3x3
uniform mat4 u_view;
uniform mat4 u_projection;

out vec3 v_world;
out vec3 v_normal;
out vec3 v_color;
out float v_view_depth;
out vec2 v_uv;

void main() {
  vec4 world = u_model * vec4(a_position, 1.0);
  vec4 view = u_view * world;
  v_world = world.xyz;
  v_normal = u_normal_matrix * a_normal;
  v_color = a_color;
  v_uv = a_uv;
  v_view_depth = -view.z;  // distance along the viewing axis, positive in front of the camera
  gl_Position = u_projection * view;
}
