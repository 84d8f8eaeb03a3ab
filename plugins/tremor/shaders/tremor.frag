// Screen-space hand tremor (plugins/tremor/README.md): each pixel reads the image displaced by
//   offset = amplitude · m · (perlin3(p / size_px, t·speed, 0), perlin3(p / size_px, t·speed, 7.31))
// pixels, m = the control map's alpha clamped to [0, 2] (1 when unconnected). Time is the noise's third axis, so
// the wobble moves smoothly from frame to frame. A zero offset reads the texel itself.
// aq_epilogue: the pointwise nodes after the tremor (paper relief, tint) when the host fuses
// them into this pass (AQ_NODE_EPILOGUE), else the identity.
#include "aquarelle/noise.glsl"
#include "aquarelle/integer_division.glsl"

in vec2 v_uv;
out vec4 o_color;

uniform sampler2D u_image;
uniform sampler2D u_control;
uniform int u_has_control;
uniform float u_amplitude;  // working pixels
uniform float u_wavelength;  // working pixels
uniform float u_phase;      // time · speed
uniform float u_max_mask;   // the mask is clamped to this (control_map writes at most 2)

void main() {
  ivec2 p = ivec2(gl_FragCoord.xy);
  ivec2 size = textureSize(u_image, 0);
  float m = 1.0;
  if (u_has_control != 0) {
    ivec2 csize = textureSize(u_control, 0);
    m = texelFetch(u_control, min(aq_scaled_texel(p, size, csize), csize - 1), 0).a;
    if (!(m > 0.0) || isinf(m)) m = 0.0;
    m = min(m, u_max_mask);
  }
  if (m == 0.0) {
    o_color = aq_epilogue(texelFetch(u_image, p, 0));
    return;
  }
  vec2 q = gl_FragCoord.xy / u_wavelength;
  vec2 offset = u_amplitude * m *
                vec2(aq_perlin3(vec3(q, u_phase), vec3(0.0)),
                     aq_perlin3(vec3(q + vec2(7.31, 3.17), u_phase + 11.7), vec3(0.0)));
  o_color = aq_epilogue(texture(u_image, (gl_FragCoord.xy + offset) / vec2(size)));
}
