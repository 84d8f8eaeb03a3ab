// One level down the reduced-resolution pyramid: each texel is the mean of a 2×2 block of the
// level above, read with one bilinear fetch at the block's centre (an odd last row or column
// averages the edge texel with its clamp-to-edge copy). Per axis this is a box of two taps half
// a source texel either side: variance (source texel / 2)².
layout(location = 0) out vec4 o_color;

uniform sampler2D u_image;
uniform vec2 u_source_size;  // size of the level above, texels

void main() {
  // Target texel i covers source texels 2i and 2i + 1, whose shared edge is at 2·(i + ½).
  o_color = texture(u_image, 2.0 * gl_FragCoord.xy / u_source_size);
}
