// The input decoded from AQ_FORMAT_RGBA8_HDR (aquarelle/hdr8.glsl) for the blur methods whose
// shaders filter with the hardware (blur.cpp); the separable direct kernel decodes per tap.
#include "aquarelle/hdr8.glsl"
layout(location = 0) out vec4 o_color;
uniform sampler2D u_image;
void main() { o_color = aq_hdr8_decode(texelFetch(u_image, ivec2(gl_FragCoord.xy), 0)); }
