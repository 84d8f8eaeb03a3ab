// pigment_mix: out.rgb = mix(a.rgb, b.rgb, factor · b.a) as light (rgb), as the seed's CMYK
// interpolation, or as Kubelka–Munk pigments (aquarelle/pigment.glsl); out.a = a.a.
// The node defines AQ_PIGMENT_MODE (0 rgb, 1 cmyk, 2 km) before this text.
#include "aquarelle/pigment.glsl"
layout(location = 0) out vec4 o_color;

uniform sampler2D u_a;
uniform sampler2D u_b;
uniform float u_factor;

void main() {
  vec4 a = texelFetch(u_a, ivec2(gl_FragCoord.xy), 0);
  vec4 b = texture(u_b, gl_FragCoord.xy / vec2(textureSize(u_a, 0)));
  float t = u_factor * (b.a >= 0.0 ? min(b.a, 1.0) : 0.0);
#if AQ_PIGMENT_MODE == 0
  vec3 c = aq_mix_rgb(a.rgb, b.rgb, t);
#elif AQ_PIGMENT_MODE == 1
  vec3 c = aq_mix_cmyk(a.rgb, b.rgb, t);
#else
  vec3 c = aq_mix_km(a.rgb, b.rgb, t);
#endif
  o_color = vec4(c, a.a == a.a && abs(a.a) <= 3.0e38 ? a.a : 0.0);
}
