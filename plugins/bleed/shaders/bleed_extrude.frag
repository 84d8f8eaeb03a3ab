// Bleed extrusion (plugins/bleed/README.md; seed 002 pushes the bleeding geometry out along its
// normals before the blur), in screen space: a texel x is covered by the nearest texel y (least
// depth; the first in row order on a tie) of another object with bleed b(y) > 0, in front of it
// (depth(y) < depth(x)), within extrude · b(y) pixels of it (centre to centre, Euclidean, a
// texel being `u_spacing` pixels: 1 for the exact operator, the cell's side on cells). A covered
// texel takes y's colour and key, and its key's w is 1 (else 0): the colour runs past the
// silhouette as far as the bleed asks before the gated blur spreads it.
in vec2 v_uv;
layout(location = 0) out vec4 o_color;
layout(location = 1) out vec4 o_key;

uniform sampler2D u_color;
uniform sampler2D u_key;  // (bleed, depth, id, ·)
uniform float u_spacing;  // pixels per texel
uniform float u_extrude;  // pixels at bleed 1
uniform int u_radius;     // ceil(extrude / spacing): texels searched each way

void main() {
  ivec2 size = textureSize(u_key, 0);
  ivec2 x = ivec2(gl_FragCoord.xy);
  vec4 own = texelFetch(u_key, x, 0);
  ivec2 best = x;
  float best_depth = own.y;
  bool covered = false;
  for (int j = -u_radius; j <= u_radius; ++j)
    for (int i = -u_radius; i <= u_radius; ++i) {
      ivec2 y = x + ivec2(i, j);
      if (any(lessThan(y, ivec2(0))) || any(greaterThanEqual(y, size))) continue;
      vec4 key = texelFetch(u_key, y, 0);
      if (!(key.x > 0.0) || key.z == own.z || !(key.y < best_depth)) continue;
      if (length(vec2(i, j)) * u_spacing > u_extrude * key.x) continue;
      best = y;
      best_depth = key.y;
      covered = true;
    }
  if (!covered) {
    o_color = texelFetch(u_color, x, 0);
    o_key = vec4(own.xyz, 0.0);
    return;
  }
  o_color = texelFetch(u_color, best, 0);
  o_key = vec4(texelFetch(u_key, best, 0).xyz, 1.0);
}
