// The paper the layers are glazed on: paper_color · (1 + paper_relief · (height − ½)), into
// both ping-pong textures at once (location 1 is ignored when only one target is bound).
layout(location = 0) out vec4 o_color;
layout(location = 1) out vec4 o_copy;
uniform sampler2D u_paper;
uniform vec3 u_paper_color;
uniform float u_paper_relief;
uniform vec2 u_size;

void main() {
#if AQ_HAS_PAPER
  float h = texture(u_paper, gl_FragCoord.xy / u_size).r;
  h = h >= 0.0 ? min(h, 1.0) : 0.5;
#else
  float h = 0.5;
#endif
  o_color = vec4(u_paper_color * (1.0 + u_paper_relief * (h - 0.5)), 1.0);
  o_copy = o_color;
}
