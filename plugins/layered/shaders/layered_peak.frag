// One axis of the running maximum of the blurred masks over (2r+1) texels (clamped to the
// image): two passes give each layer's peak over a (2r+1)^2 window, which tells a thin shape
// (it is its own peak, however low) from the rounded-off corner of a wide one (README:
// "Thin shapes").
layout(location = 0) out vec4 o_peak;

uniform sampler2D u_source;
uniform ivec2 u_axis;
uniform int u_radius;

void main() {
  ivec2 p = ivec2(gl_FragCoord.xy);
  ivec2 last = textureSize(u_source, 0) - 1;
  vec4 m = texelFetch(u_source, p, 0);
  for (int i = 1; i <= u_radius; ++i) {
    m = max(m, texelFetch(u_source, clamp(p + i * u_axis, ivec2(0), last), 0));
    m = max(m, texelFetch(u_source, clamp(p - i * u_axis, ivec2(0), last), 0));
  }
  o_peak = m;
}
