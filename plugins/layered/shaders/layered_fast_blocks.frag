// The `fast` method's cell blocks (README "Fast method", "Cells"): 2 x 2 texels per cell, one
// per corner, holding that corner texel's values re-keyed to the cell's merged, ordered list
// (layered_fast_cells.frag). A bilinear fetch inside a cell's block, at 2c + ½ + f texels, so
// interpolates the four corners with the weights of the full-size pixel's position f in the
// cell: per layer one fetch of (b, bd, bz, wet edge) and one of the peaks for all four, the
// same wherever the corners' lists differ (no merging per pixel).
layout(location = 0) out vec4 o_slot0;  // slot k: (blurred I, D, Z, blurred wet edge)
layout(location = 1) out vec4 o_slot1;
layout(location = 2) out vec4 o_slot2;
layout(location = 3) out vec4 o_slot3;
layout(location = 4) out vec4 o_peak;  // the thin shapes' peaks of the four slots

uniform sampler2D u_cells;  // the cells' merged, ordered keys
uniform sampler2D u_keys;   // the blurred lists' keys
uniform sampler2D u_blur_intensity;
uniform sampler2D u_blur_diffuse;
uniform sampler2D u_blur_depth;
uniform sampler2D u_blur_edges;
uniform sampler2D u_peak;

void main() {
  ivec2 size = textureSize(u_keys, 0);
  ivec2 p = ivec2(gl_FragCoord.xy);
  ivec2 cell = p >> 1;
  ivec2 t = list_clamp(cell - 1 + (p & 1), size);  // this corner's texel
  mat4 m = list_match(texelFetch(u_cells, cell, 0), texelFetch(u_keys, t, 0));
  vec4 b = m * texelFetch(u_blur_intensity, t, 0);
  vec4 bd = m * texelFetch(u_blur_diffuse, t, 0);
  vec4 bz = m * texelFetch(u_blur_depth, t, 0);
  vec4 e = m * texelFetch(u_blur_edges, t, 0);
  o_slot0 = vec4(b.x, bd.x, bz.x, e.x);
  o_slot1 = vec4(b.y, bd.y, bz.y, e.y);
  o_slot2 = vec4(b.z, bd.z, bz.z, e.z);
  o_slot3 = vec4(b.w, bd.w, bz.w, e.w);
  o_peak = m * texelFetch(u_peak, t, 0);
}
