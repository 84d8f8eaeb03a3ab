// The source averaged over 2×2 pixels (one bilinear read at the cell's centre) before the blur
// runs on the cells (plugins/edge_darkening/README.md).
in vec2 v_uv;
out vec4 o_color;

uniform sampler2D u_source;

void main() {
  vec2 size = vec2(textureSize(u_source, 0));
  o_color = texture(u_source, min(2.0 * gl_FragCoord.xy, size) / size);
}
