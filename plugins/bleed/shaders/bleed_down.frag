// One cell of the downsampled bleed (plugins/bleed/README.md): of the cell's F×F pixels the
// nearest (least depth; the first on a tie) represents it. The cell's colour is the mean of the
// finite pixels that may run into the representative (same id, or not behind it by more than
// the bias), its bleed the largest of theirs: a farther object's colour never enters a cell a
// nearer one represents. Outputs (colour) and (bleed, depth, id, 0) of the representative.
// bleed_inputs.glsl is prepended: the node's inputs are read directly, no full-size key.
in vec2 v_uv;
layout(location = 0) out vec4 o_color;
layout(location = 1) out vec4 o_key;

uniform sampler2D u_color;
uniform int u_cell;
uniform float u_depth_bias;

bool finite4(vec4 c) { return !any(isnan(c)) && !any(isinf(c)); }

void main() {
  ivec2 size = textureSize(u_color, 0);
  ivec2 origin = ivec2(gl_FragCoord.xy) * u_cell;
  ivec2 last = min(origin + u_cell, size) - 1;
  ivec2 nearest = origin;
  float nearest_depth = bleed_depth(origin);
  for (int y = origin.y; y <= last.y; ++y)
    for (int x = origin.x; x <= last.x; ++x) {
      float depth = bleed_depth(ivec2(x, y));
      if (depth < nearest_depth) {
        nearest_depth = depth;
        nearest = ivec2(x, y);
      }
    }
  float nearest_id = bleed_id(nearest);
  vec4 sum = vec4(0.0);
  float count = 0.0, bleed = 0.0;
  for (int y = origin.y; y <= last.y; ++y)
    for (int x = origin.x; x <= last.x; ++x) {
      ivec2 p = ivec2(x, y);
      if (!(bleed_id(p) == nearest_id || bleed_depth(p) <= nearest_depth + u_depth_bias)) continue;
      vec4 c = texelFetch(u_color, p, 0);
      if (!finite4(c)) continue;
      sum += c;
      count += 1.0;
      bleed = max(bleed, bleed_amount(p));
    }
  o_color = count > 0.0 ? sum / count : vec4(0.0);
  o_key = vec4(bleed, nearest_depth, nearest_id, 0.0);
}
