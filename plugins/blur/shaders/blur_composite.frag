// Variable blur from a stack of exact Gaussian blurs: level 0 is the input (σ = 0), levels
// 1..n are blurred with increasing σ. A pixel wanting σ between two levels mixes them with
// t = (σ² − σa²) / (σb² − σa²), so the mixed kernel has exactly the wanted variance σ².
in vec2 v_uv;
layout(location = 0) out vec4 o_color;

uniform sampler2D u_level0;
uniform sampler2D u_level1;
uniform sampler2D u_level2;
uniform sampler2D u_level3;
uniform sampler2D u_level4;
uniform sampler2D u_level5;
uniform sampler2D u_level6;
uniform sampler2D u_level7;
uniform sampler2D u_level8;
uniform sampler2D u_level9;
uniform sampler2D u_level10;
uniform sampler2D u_level11;
uniform sampler2D u_level12;
uniform float u_level_sigma[13];  // ascending, u_level_sigma[0] = 0
uniform int u_level_count;       // including level 0
uniform float u_sigma;           // σ at strength 1

float blur_strength(vec2 frag);

vec4 level(int k) {
  ivec2 p = ivec2(gl_FragCoord.xy);
  switch (k) {
    case 0: return texelFetch(u_level0, p, 0);
    case 1: return texelFetch(u_level1, p, 0);
    case 2: return texelFetch(u_level2, p, 0);
    case 3: return texelFetch(u_level3, p, 0);
    case 4: return texelFetch(u_level4, p, 0);
    case 5: return texelFetch(u_level5, p, 0);
    case 6: return texelFetch(u_level6, p, 0);
    case 7: return texelFetch(u_level7, p, 0);
    case 8: return texelFetch(u_level8, p, 0);
    case 9: return texelFetch(u_level9, p, 0);
    case 10: return texelFetch(u_level10, p, 0);
    case 11: return texelFetch(u_level11, p, 0);
    default: return texelFetch(u_level12, p, 0);
  }
}

void main() {
  float sigma = u_sigma * blur_strength(gl_FragCoord.xy);
  int top = u_level_count - 1;
  if (sigma >= u_level_sigma[top]) {
    o_color = level(top);
    return;
  }
  int k = 0;
  while (k + 1 < top && u_level_sigma[k + 1] < sigma) ++k;
  float a = u_level_sigma[k];
  float b = u_level_sigma[k + 1];
  float t = (sigma * sigma - a * a) / (b * b - a * a);
  if (t <= 0.0) {
    o_color = level(k);
  } else {
    o_color = mix(level(k), level(k + 1), t);
  }
}
