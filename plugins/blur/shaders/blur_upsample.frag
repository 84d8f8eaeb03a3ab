// Back from the reduced-resolution pyramid: bilinear interpolation of a level at scale s
// (reduced texel i covers full-resolution pixels s·i .. s·i + s − 1, so its centre is at
// s·(i + ½)). Per axis a pixel at fraction t between two reduced texels gets variance
// t(1 − t)·s²; over the pixels of a block the mean is (2s² + 1)/12 (README).
layout(location = 0) out vec4 o_color;

uniform sampler2D u_image;
uniform vec2 u_reduced_extent;  // s · reduced size, in full-resolution pixels

void main() {
  o_color = texture(u_image, gl_FragCoord.xy / u_reduced_extent);
}
