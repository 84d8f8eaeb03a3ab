// The control map's depth pre-pass: only the cut-outs' test (one texture read), so the FBM of
// control_map.frag then runs once per visible pixel instead of once per overlapping fragment.
in vec3 v_object;
in vec3 v_world;
in vec3 v_normal;
in vec2 v_uv;

uniform sampler2D u_base_color;
uniform float u_alpha_cutoff;

void main() {
  if (texture(u_base_color, v_uv).a < u_alpha_cutoff) discard;  // the gbuffer's cut-outs
}
