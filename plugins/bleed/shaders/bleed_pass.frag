// One 1D pass of the gated bleeding blur (plugins/bleed/README.md). For the pixel x and each tap
// y = x + i·direction (clamped to the image), y takes part when it may run into x:
//   same id, or y not behind x (depth(y) <= depth(x) + bias)
// and its colour is finite. Gaussian weights of the taps that take part are renormalised; the
// amount is the largest bleed among them. The second pass (u_final = 1) mixes the original
// colour with the blurred one by that amount; amount 0 returns the original texel unchanged.
// The key's w says whether a cell's 2×2 block holds one id (for bleed_up.frag; ids do not move
// in the passes, so the vertical pass's answer is the cells').
in vec2 v_uv;
layout(location = 0) out vec4 o_color;
layout(location = 1) out vec4 o_key;

uniform sampler2D u_color;     // colour to blur (pass 1: the image; pass 2: pass 1's colour)
uniform sampler2D u_key;       // (amount, depth, id): pass 1 the packed key, pass 2 pass 1's
uniform sampler2D u_original;  // the image (pass 2's centre colour)
uniform ivec2 u_direction;
uniform int u_radius;
uniform float u_inv_two_sigma2;
uniform float u_depth_bias;
uniform int u_final;

bool finite4(vec4 c) { return !any(isnan(c)) && !any(isinf(c)); }

void main() {
  ivec2 size = textureSize(u_color, 0);
  ivec2 x = ivec2(gl_FragCoord.xy);
  vec4 centre_key = texelFetch(u_key, x, 0);
  vec4 sum = vec4(0.0);
  float weights = 0.0;
  float amount = 0.0;
  for (int i = -u_radius; i <= u_radius; ++i) {
    ivec2 y = clamp(x + i * u_direction, ivec2(0), size - 1);
    vec4 key = texelFetch(u_key, y, 0);
    bool may_run = key.z == centre_key.z || key.y <= centre_key.y + u_depth_bias;
    if (!may_run) continue;
    vec4 c = texelFetch(u_color, y, 0);
    if (!finite4(c)) continue;
    float w = exp(-float(i * i) * u_inv_two_sigma2);
    sum += w * c;
    weights += w;
    amount = max(amount, key.x);
  }
  vec4 blurred = weights > 0.0 ? sum / weights : texelFetch(u_color, x, 0);
  if (u_final == 0) {
    // w: 1 where this cell and its neighbours at +x, +y and +xy (clamped) hold one id, so the
    // upsampling (bleed_up.frag) may read the four by bilinear filtering.
    float same = 1.0;
    for (int k = 1; k < 4; ++k) {
      ivec2 n = min(x + ivec2(k & 1, k >> 1), size - 1);
      if (texelFetch(u_key, n, 0).z != centre_key.z) same = 0.0;
    }
    o_color = blurred;
    o_key = vec4(amount, centre_key.yz, same);
    return;
  }
  vec4 original = texelFetch(u_original, x, 0);
  o_color = amount > 0.0 ? mix(original, blurred, amount) : original;
  o_key = vec4(0.0);
}
