// The input decoded from AQ_FORMAT_RGBA8_HDR (aquarelle/hdr8.glsl) for the blur methods whose
// shaders filter with the hardware (blur.cpp); the separable direct kernel decodes per tap.
#include "aquarelle/hdr8.glsl"
// blur.cpp defines AQ_BLOCKS 1 for an input in 2 x 2 blocks (AQ_FORMAT_RGBA8_HDR_BLOCKS).
layout(location = 0) out vec4 o_color;
#if AQ_BLOCKS
uniform usampler2D u_blocks;
void main() { o_color = aq_hdr8_block_pixel(u_blocks, ivec2(gl_FragCoord.xy)); }
#else
uniform sampler2D u_image;
void main() { o_color = aq_hdr8_decode(texelFetch(u_image, ivec2(gl_FragCoord.xy), 0)); }
#endif
