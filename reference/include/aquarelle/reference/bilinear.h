// Bilinear texture lookup as OpenGL defines it for GL_LINEAR with GL_CLAMP_TO_EDGE, in double
// precision: the CPU references of nodes that sample images at arbitrary uv use it.
#pragma once

#include <aquarelle/core/image.h>

namespace aq::reference {

// Value of `channel` at texture coordinate (u, v) in [0,1]² (outside: clamped to the edge
// texels). Texel (i, j) has its centre at ((i + 0.5) / width, (j + 0.5) / height); row 0 is the
// bottom row, as in ImageF.
double sample_bilinear(const ImageF& image, double u, double v, int channel);

}  // namespace aq::reference
