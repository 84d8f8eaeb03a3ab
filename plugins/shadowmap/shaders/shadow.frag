// Writes the light-space depth (0 near the light, 1 far) plus a slope-scaled bias, the same
// quantity glPolygonOffset would add: slope_bias * max |dz/dx|, |dz/dy| per texel plus a
// constant in world units. The slope term grows at grazing light, where a surface's depth
// changes fast across one texel (acne), and stays tiny on surfaces facing the light (no
// detached shadows under the occluder). It is capped so edge-on triangles do not push depth
// to infinity.
layout(location = 0) out float o_depth;

in vec2 v_uv;
uniform sampler2D u_base_color;  // for cut-outs: the mesh's texture, or one white texel
uniform float u_alpha_cutoff;    // 0: opaque

uniform float u_slope_bias;
uniform float u_constant_bias;  // already in depth units
uniform float u_max_bias;       // depth units

void main() {
  // Holes of cut-out cards cast no shadow, as they show no surface in the g-buffer.
  if (u_alpha_cutoff > 0.0 && texture(u_base_color, v_uv).a < u_alpha_cutoff) discard;
  float z = gl_FragCoord.z;
  float slope = max(abs(dFdx(z)), abs(dFdy(z)));
  o_depth = z + min(u_slope_bias * slope + u_constant_bias, u_max_bias);
}
