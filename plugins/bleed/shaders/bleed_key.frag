// Packs what the gating needs per pixel into one texel, so each tap of the two bleed passes
// reads two textures instead of four: (bleed amount, depth, id, 0).
in vec2 v_uv;
out vec4 o_key;

uniform sampler2D u_control;
uniform sampler2D u_depth;
uniform sampler2D u_id;
uniform int u_has_depth;
uniform int u_has_id;
uniform float u_amount;

void main() {
  ivec2 p = ivec2(gl_FragCoord.xy);
  float b = texelFetch(u_control, min(p, textureSize(u_control, 0) - 1), 0).r * u_amount;
  // A NaN or negative control never bleeds; more than 1 is full bleeding.
  b = b > 0.0 ? min(b, 1.0) : 0.0;
  float depth = u_has_depth != 0 ? texelFetch(u_depth, min(p, textureSize(u_depth, 0) - 1), 0).r
                                 : 0.0;
  float id = u_has_id != 0 ? texelFetch(u_id, min(p, textureSize(u_id, 0) - 1), 0).r : 0.0;
  o_key = vec4(b, depth, id, 0.0);
}
