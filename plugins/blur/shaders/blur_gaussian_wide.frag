// One 1D pass of the exact Gaussian blur for kernels with more taps than blur_gaussian.frag's
// table holds (σ above ~120 px): the same maths, weights evaluated in the shader.
// Taps beyond the image are lumped into u_tail (see gaussian_pass.h). With u_linear_taps two neighbouring taps are read as one
// bilinear fetch placed between them in proportion to their weights, halving the reads.
in vec2 v_uv;
layout(location = 0) out vec4 o_color;

uniform sampler2D u_image;
uniform vec2 u_size;  // input size in pixels (= output size)
uniform vec2 u_step;
uniform int u_radius;
uniform float u_inv_two_sigma2;
uniform float u_norm;
uniform float u_tail;
uniform float u_tail_offset;
uniform bool u_linear_taps;

vec4 tap(float offset) {
  return texture(u_image, (gl_FragCoord.xy + offset * u_step) / u_size);
}

float weight(int i) {
  float x = float(i);
  return exp(-x * x * u_inv_two_sigma2) * u_norm;
}

void main() {
  vec4 sum = u_norm * tap(0.0);
  if (u_linear_taps) {
    for (int i = 1; i <= u_radius; i += 2) {
      float wa = weight(i);
      float wb = i + 1 <= u_radius ? weight(i + 1) : 0.0;
      float w = wa + wb;
      if (w <= 0.0) break;  // the rest underflows too
      float offset = float(i) + wb / w;
      sum += w * (tap(offset) + tap(-offset));
    }
  } else {
    for (int i = 1; i <= u_radius; ++i) {
      sum += weight(i) * (tap(float(i)) + tap(-float(i)));
    }
  }
  if (u_tail > 0.0) sum += u_tail * (tap(u_tail_offset) + tap(-u_tail_offset));
  o_color = sum;
}
