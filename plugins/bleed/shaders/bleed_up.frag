// The downsampled bleed brought back to full size and mixed (plugins/bleed/README.md): the four
// nearest cells whose representative may run into this pixel (same id, or not behind it by more
// than the bias), bilinear weights renormalised over them, give the blurred colour B and the
// amount A; out = A > 0 ? mix(C, B, A) : C (the texel unchanged). No cell may run in: C.
// Where the four cells all hold the pixel's id (the cells' key says so in w) every one may run
// in and the weights sum to 1: two bilinear reads give B and A, the same sums. bleed_inputs.glsl
// is prepended: the pixel's depth and id are read from the node's inputs. With extrusion, a
// pixel whose own cell the extruded geometry covers takes that geometry's colour, id and depth.
#include "aquarelle/integer_division.glsl"

in vec2 v_uv;
out vec4 o_color;

uniform sampler2D u_original;
uniform sampler2D u_cell_color;   // blurred cells
uniform sampler2D u_cell_key;     // (amount, depth, id, 1 where the 2×2 block shares the id)
uniform int u_cell;
uniform float u_depth_bias;
uniform int u_extruded;               // 1: the cells were extruded (bleed_extrude.frag)
uniform sampler2D u_cell_source;      // the extruded cells' colour, before the blur
uniform sampler2D u_cell_source_key;  // their key; w = 1 where extruded geometry covers the cell

void main() {
  ivec2 x = ivec2(gl_FragCoord.xy);
  vec4 original = texelFetch(u_original, x, 0);
  ivec2 cells = textureSize(u_cell_key, 0);
  vec2 f = (vec2(x) + 0.5) / float(u_cell) - 0.5;
  ivec2 base = ivec2(floor(f));
  float id = bleed_id(x);
  // A pixel whose own cell extruded geometry covers (of another id, in front of it) is that
  // geometry: its colour, id and depth.
  bool covered = false;
  float covered_depth = 0.0;
  if (u_extruded != 0) {
    ivec2 own = min(aq_floor_divide(x, ivec2(u_cell)), cells - 1);
    vec4 source_key = texelFetch(u_cell_source_key, own, 0);
    if (source_key.w > 0.5 && source_key.z != id && source_key.y < bleed_depth(x)) {
      covered = true;
      original = texelFetch(u_cell_source, own, 0);
      id = source_key.z;
      covered_depth = source_key.y;
    }
  }
  vec4 block = texelFetch(u_cell_key, clamp(base, ivec2(0), cells - 1), 0);
  if (block.w > 0.5 && block.z == id) {
    vec2 uv = (f + 0.5) / vec2(cells);
    float shared_amount = texture(u_cell_key, uv).x;
    o_color = shared_amount > 0.0 ? mix(original, texture(u_cell_color, uv), shared_amount)
                                  : original;
    return;
  }
  float depth = covered ? covered_depth : bleed_depth(x);
  vec2 frac = f - vec2(base);
  vec4 sum = vec4(0.0);
  float weights = 0.0, amount = 0.0;
  for (int j = 0; j < 2; ++j)
    for (int i = 0; i < 2; ++i) {
      ivec2 k = clamp(base + ivec2(i, j), ivec2(0), cells - 1);
      vec4 cell_key = texelFetch(u_cell_key, k, 0);
      if (!(cell_key.z == id || cell_key.y <= depth + u_depth_bias)) continue;
      float w = (i == 0 ? 1.0 - frac.x : frac.x) * (j == 0 ? 1.0 - frac.y : frac.y);
      if (!(w > 0.0)) continue;
      sum += w * texelFetch(u_cell_color, k, 0);
      amount += w * cell_key.x;
      weights += w;
    }
  if (!(weights > 0.0) || !(amount > 0.0)) {
    o_color = original;
    return;
  }
  o_color = mix(original, sum / weights, amount / weights);
}
