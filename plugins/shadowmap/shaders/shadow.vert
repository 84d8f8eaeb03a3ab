// Scene vertices into the light's orthographic clip space.
layout(location = 0) in vec3 a_position;
layout(location = 3) in vec2 a_uv;  // for cut-out textures

uniform mat4 u_model;
uniform mat4 u_light_view_projection;

out vec2 v_uv;

void main() {
  v_uv = a_uv;
  gl_Position = u_light_view_projection * u_model * vec4(a_position, 1.0);
}
