in vec2 v_uv;
layout(location = 0) out vec4 o_color;
uniform sampler2D u_image;
void main() {
  vec4 c = texture(u_image, v_uv);
  o_color = vec4(1.0 - c.rgb, c.a);
}
