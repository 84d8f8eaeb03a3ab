// A gradient with a bright HDR square at u_square (x0, y0, x1, y1 in pixels): a picture whose
// change from frame to frame is known exactly (test_square, damage tracking tests).
in vec2 v_uv;
layout(location = 0) out vec4 o_color;
uniform vec4 u_square;
void main() {
  vec2 p = gl_FragCoord.xy;
  bool inside = p.x >= u_square.x && p.x < u_square.z && p.y >= u_square.y && p.y < u_square.w;
  o_color = inside ? vec4(4.0, 3.0, 0.5, 1.0) : vec4(v_uv.x, v_uv.y, 0.3 + 0.4 * v_uv.x * v_uv.y, 1.0);
}
