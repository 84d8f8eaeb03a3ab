// The paper height's gradient by central differences, one texel either side, halved: what
// `wobble` would otherwise compute per pixel from four bilinear reads of the height. Shifting
// by exactly one texel commutes with bilinear filtering, so a bilinear read of this texture
// equals wobble's own differences of bilinear reads, except within half a texel of the border
// where the edge clamp applies before instead of after the difference.
// paper.cpp defines AQ_PAPER_COPY_HEIGHT 1 when the `image` output is stored in 8 bits: the
// height then comes from a full-precision scratch image and is copied to the second target.
#ifndef AQ_PAPER_COPY_HEIGHT
#define AQ_PAPER_COPY_HEIGHT 0
#endif
uniform sampler2D u_height;

layout(location = 0) out vec4 o_color;
#if AQ_PAPER_COPY_HEIGHT
layout(location = 1) out vec4 o_height;
#endif

float height_at(ivec2 p) {
  ivec2 last = textureSize(u_height, 0) - 1;
  return texelFetch(u_height, clamp(p, ivec2(0), last), 0).r;
}

void main() {
  ivec2 p = ivec2(gl_FragCoord.xy);
  vec2 gradient = vec2(height_at(p + ivec2(1, 0)) - height_at(p - ivec2(1, 0)),
                       height_at(p + ivec2(0, 1)) - height_at(p - ivec2(0, 1))) /
                  2.0;
  o_color = vec4(gradient, 0.0, 1.0);
#if AQ_PAPER_COPY_HEIGHT
  o_height = texelFetch(u_height, p, 0);
#endif
}
