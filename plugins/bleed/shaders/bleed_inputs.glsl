// What the gating reads per pixel, from the node's own inputs (plugins/bleed/README.md): the
// bleed amount clamp(control.r · amount, 0, 1) (NaN and negatives 0), the linear depth (0
// without a depth input) and the object id (0 without an id input). Prepended by bleed.cpp to
// the key pass and to the passes that go to and from the cells, which read them directly.
uniform sampler2D u_control;
uniform sampler2D u_depth;
uniform sampler2D u_id;
uniform int u_has_depth;
uniform int u_has_id;
uniform float u_amount;

float bleed_amount(ivec2 p) {
  float b = texelFetch(u_control, min(p, textureSize(u_control, 0) - 1), 0).r * u_amount;
  return b > 0.0 ? min(b, 1.0) : 0.0;  // a NaN or negative control never bleeds
}

float bleed_depth(ivec2 p) {
  return u_has_depth != 0 ? texelFetch(u_depth, min(p, textureSize(u_depth, 0) - 1), 0).r : 0.0;
}

float bleed_id(ivec2 p) {
  return u_has_id != 0 ? texelFetch(u_id, min(p, textureSize(u_id, 0) - 1), 0).r : 0.0;
}
