// The composite's classes (README "Fast method"): each pixel's depth is set to (n + 1) / 8,
// n = 1 + the index of the last listed layer of its cell (0 when none is; 3 for three or four),
// so that the four draws of layered_fast_composite.frag, each with AQ_LAYER_COUNT n (4 for
// n = 3) and the depth range [d, d] under the depth test EQUAL, shade every pixel once, with
// only the layers it may list. Three and four share a class: few pixels list them (1.6 % in
// layered.json), and a draw whose pixels all fail the depth test still costs llvmpipe about
// half a millisecond at 720p. The cell is the composite's: between the lists' texels at base
// and base + 1.
layout(location = 0) out vec4 o_color;

uniform sampler2D u_cells;  // per cell its merged keys, far to near (layered_fast_cells.frag)

void main() {
  ivec2 cell = ivec2(floor(gl_FragCoord.xy / float(AQ_DIVISOR) - 0.5)) + 1;
  vec4 keys = texelFetch(u_cells, cell, 0);
  float n = keys.z > 0.5 ? 3.0 : keys.y > 0.5 ? 2.0 : keys.x > 0.5 ? 1.0 : 0.0;
  gl_FragDepth = (n + 1.0) / 8.0;
  o_color = vec4(0.0);  // every pixel is drawn again by its class
}
