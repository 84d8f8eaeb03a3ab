// The seed's blur, kept to show its artefacts: a 5×5 binomial kernel ([1 4 6 4 1]/16 per axis,
// σ = 1 tap) read with strides 0.3σ and σ (σ = 10 gives the seed's 3 and 10 pixels), mixed
// with the sharp colour: s in [0, ½] mixes colour → stride-a blur, s in [½, 1] mixes
// stride-a → stride-b blur. Only 25 taps whatever the stride: sparse sampling aliases.
in vec2 v_uv;
layout(location = 0) out vec4 o_color;

uniform sampler2D u_image;
uniform float u_sigma;

float blur_strength(vec2 frag);

const float kBinomial[5] = float[5](1.0, 4.0, 6.0, 4.0, 1.0);

vec4 strided(float stride) {
  vec4 sum = vec4(0.0);
  for (int j = 0; j < 5; ++j) {
    for (int i = 0; i < 5; ++i) {
      vec2 offset = vec2(float(i - 2), float(j - 2)) * stride;
      sum += kBinomial[i] * kBinomial[j] * texture(u_image, (gl_FragCoord.xy + offset) / u_size);
    }
  }
  return sum / 256.0;
}

void main() {
  float s = blur_strength(gl_FragCoord.xy);
  vec4 sharp = texelFetch(u_image, ivec2(gl_FragCoord.xy), 0);
  if (s <= 0.0) {
    o_color = sharp;
  } else if (s <= 0.5) {
    o_color = mix(sharp, strided(0.3 * u_sigma), 2.0 * s);
  } else {
    o_color = mix(strided(0.3 * u_sigma), strided(u_sigma), 2.0 * s - 1.0);
  }
}
