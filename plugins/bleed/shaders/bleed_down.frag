// One cell of the downsampled bleed (plugins/bleed/README.md): of the cell's F×F pixels the
// nearest (least depth; the first on a tie) represents it. The cell's colour is the mean of the
// finite pixels that may run into the representative (same id, or not behind it by more than
// the bias), its bleed the largest of theirs: a farther object's colour never enters a cell a
// nearer one represents. Outputs (colour) and (bleed, depth, id, 0) of the representative.
in vec2 v_uv;
layout(location = 0) out vec4 o_color;
layout(location = 1) out vec4 o_key;

uniform sampler2D u_color;
uniform sampler2D u_key;  // (bleed, depth, id, 0) per pixel
uniform int u_cell;
uniform float u_depth_bias;

bool finite4(vec4 c) { return !any(isnan(c)) && !any(isinf(c)); }

void main() {
  ivec2 size = textureSize(u_color, 0);
  ivec2 origin = ivec2(gl_FragCoord.xy) * u_cell;
  ivec2 last = min(origin + u_cell, size) - 1;
  vec4 representative = texelFetch(u_key, origin, 0);
  for (int y = origin.y; y <= last.y; ++y)
    for (int x = origin.x; x <= last.x; ++x) {
      vec4 key = texelFetch(u_key, ivec2(x, y), 0);
      if (key.y < representative.y) representative = key;
    }
  vec4 sum = vec4(0.0);
  float count = 0.0, bleed = 0.0;
  for (int y = origin.y; y <= last.y; ++y)
    for (int x = origin.x; x <= last.x; ++x) {
      vec4 key = texelFetch(u_key, ivec2(x, y), 0);
      if (!(key.z == representative.z || key.y <= representative.y + u_depth_bias)) continue;
      vec4 c = texelFetch(u_color, ivec2(x, y), 0);
      if (!finite4(c)) continue;
      sum += c;
      count += 1.0;
      bleed = max(bleed, key.x);
    }
  o_color = count > 0.0 ? sum / count : vec4(0.0);
  o_key = vec4(bleed, representative.yz, 0.0);
}
