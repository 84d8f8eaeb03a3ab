// out = in + offset (or offset alone when no input): cheap, exact, easy to predict.
in vec2 v_uv;
layout(location = 0) out vec4 o_color;
uniform sampler2D u_image;
uniform bool u_has_image;
uniform float u_offset;
void main() {
  vec4 c = u_has_image ? texture(u_image, v_uv) : vec4(0.0, 0.0, 0.0, 1.0);
  o_color = vec4(c.rgb + vec3(u_offset), c.a);
}
