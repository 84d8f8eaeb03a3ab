// Packs what the gating needs per pixel into one texel, so each tap of the two exact bleed
// passes reads two textures instead of four: (bleed amount, depth, id, 0). bleed_inputs.glsl
// is prepended.
in vec2 v_uv;
out vec4 o_key;

void main() {
  ivec2 p = ivec2(gl_FragCoord.xy);
  o_key = vec4(bleed_amount(p), bleed_depth(p), bleed_id(p), 0.0);
}
