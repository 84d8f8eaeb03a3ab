// Variable blur from a stack of exact Gaussian blurs: level 0 is the input (σ = 0), levels
// 1..n are blurred with increasing σ. A pixel wanting σ between two levels mixes them with
// t = (σ² − σa²) / (σb² − σa²), so the mixed kernel has exactly the wanted variance σ².
// blur.cpp prepends AQ_LEVEL_COUNT (levels including level 0) and AQ_HAS_DEPTH and the
// strength function: each pixel reads exactly the stack's levels, no more (a switch over
// samplers costs every case on llvmpipe), and the mixing weights are "hat" functions of σ²
// evaluated arithmetically, one per level, instead of a search through the levels.
layout(location = 0) out vec4 o_color;

uniform sampler2D u_levels[AQ_LEVEL_COUNT];
uniform float u_level_sigma2[AQ_LEVEL_COUNT];  // σ² of each level, ascending, [0] = 0
uniform float u_rise[AQ_LEVEL_COUNT];  // 1 / (σk² − σk−1²); [0] unused
uniform float u_fall[AQ_LEVEL_COUNT];  // 1 / (σk+1² − σk²); [n−1] unused
uniform float u_sigma;                 // σ at strength 1

float blur_strength(vec2 frag);

void main() {
  ivec2 p = ivec2(gl_FragCoord.xy);
  float sigma = u_sigma * blur_strength(gl_FragCoord.xy);
  float s2 = sigma * sigma;
  vec4 sum = vec4(0.0);
  // A constant trip count: the compiler unrolls it, so every index below is a constant.
  for (int k = 0; k < AQ_LEVEL_COUNT; ++k) {
    // Weight of level k: rises from 0 at the level below to 1 at σk², falls to 0 at the level
    // above. Level 0 has no rise (σ² >= 0), the top level no fall (σ beyond it takes it).
    float rise = k == 0 ? 1.0 : (s2 - u_level_sigma2[max(k - 1, 0)]) * u_rise[k];
    float fall =
        k == AQ_LEVEL_COUNT - 1 ? 1.0 : (u_level_sigma2[min(k + 1, AQ_LEVEL_COUNT - 1)] - s2) * u_fall[k];
    float w = clamp(min(rise, fall), 0.0, 1.0);
    // A select, so that a level with weight 0 cannot bring in 0 · ∞ = NaN.
    vec4 level = texelFetch(u_levels[k], p, 0);
    sum += w > 0.0 ? w * level : vec4(0.0);
  }
  o_color = sum;
}
