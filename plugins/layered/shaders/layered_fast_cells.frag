// The `fast` method's cells (README "Fast method", "Cells"): one texel per cell, the square
// between four neighbouring texels of the lists (cell c has the texels c − 1 and c at its
// corners, per axis, clamped to the image: (W + 1) x (H + 1) cells). Each holds the merged list
// of its four corners' layers, ordered far to near (the table's mean depth descending, then
// id; empty slots last), so the full-size composite neither merges nor sorts: it reads the
// cell and, per layer, one bilinear fetch of the cell's block (layered_fast_blocks.frag).
layout(location = 0) out vec4 o_keys;

uniform sampler2D u_keys;
uniform sampler2D u_colours;  // per slot: row 0 (…, mean depth), row 1 (…, ±id)

// Depth and id of the layer of key k (k ≤ 0.5: empty, ordered last).
vec2 order_key(float k) {
  if (!(k > 0.5)) return vec2(-3.0e38, 0.0);
  int slot = int(k) - 1;
  return vec2(texelFetch(u_colours, ivec2(slot, 0), 0).a,
              abs(texelFetch(u_colours, ivec2(slot, 1), 0).a));
}

// Puts keys a < c (constant components) far to near: c first if it lies farther, or as far
// with a smaller id.
void order_pair(inout vec4 keys, inout vec4 depth, inout vec4 id, int a, int c) {
  bool swap = depth[c] > depth[a] || (depth[c] == depth[a] && id[c] < id[a]);
  vec3 x = vec3(keys[a], depth[a], id[a]);
  vec3 y = vec3(keys[c], depth[c], id[c]);
  vec3 first = swap ? y : x, second = swap ? x : y;
  keys[a] = first.x;
  depth[a] = first.y;
  id[a] = first.z;
  keys[c] = second.x;
  depth[c] = second.y;
  id[c] = second.z;
}

void main() {
  ivec2 size = textureSize(u_keys, 0);
  ivec2 c = ivec2(gl_FragCoord.xy) - 1;  // the cell's bottom-left texel
  vec4 keys = vec4(0.0);
  for (int n = 0; n < 4; ++n) {
    list_merge(keys, texelFetch(u_keys, list_clamp(c + ivec2(n & 1, n >> 1), size), 0));
  }
  vec4 depth, id;
  for (int k = 0; k < 4; ++k) {
    vec2 o = order_key(keys[k]);
    depth[k] = o.x;
    id[k] = o.y;
  }
  order_pair(keys, depth, id, 0, 1);
  order_pair(keys, depth, id, 2, 3);
  order_pair(keys, depth, id, 0, 2);
  order_pair(keys, depth, id, 1, 3);
  order_pair(keys, depth, id, 1, 2);
  o_keys = keys;
}
