// CPU reference of the `wobble` node (plugins/wobble/README.md) in double precision: each
// output pixel looks the image up at its own centre moved by strength × the paper height's
// central-difference gradient, in paper pixels.
#pragma once

#include <aquarelle/core/image.h>

namespace aq::reference {

// `paper` (channel 0 = height) is stretched over the image; lookups are bilinear,
// clamp-to-edge, as GL_LINEAR + GL_CLAMP_TO_EDGE.
ImageF wobble(const ImageF& image, const ImageF& paper, double strength);

// The procedural paper the node renders when its `paper` input is unconnected:
// `columns` × `lines` paper pixels, cells of `grain` paper pixels, a `seed`.
ImageF procedural_paper(int columns, int lines, double grain, int seed);

// Size of the procedural paper for an image of this shape: `lines` high, width by aspect.
int procedural_paper_columns(int image_width, int image_height, int lines);

}  // namespace aq::reference
