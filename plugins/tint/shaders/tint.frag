// out = mix(colour, tint, amount); alpha is kept. amount 0 and 1 are exact because mix is
// evaluated as c + (t - c) * a only inside (0, 1).
in vec2 v_uv;
layout(location = 0) out vec4 o_color;

uniform sampler2D u_image;
uniform vec3 u_tint;
uniform float u_amount;

void main() {
  vec4 c = texture(u_image, v_uv);
  vec3 rgb = u_amount <= 0.0 ? c.rgb : (u_amount >= 1.0 ? u_tint : mix(c.rgb, u_tint, u_amount));
  o_color = vec4(rgb, c.a);
}
