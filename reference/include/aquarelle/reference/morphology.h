// CPU reference for the `erode` and `dilate` nodes, written from the definition of flat
// morphology (not from the two-pass shader): for each pixel, the minimum (erosion) or maximum
// (dilation) over every pixel of the footprint, coordinates clamped to the image.
#pragma once

#include <aquarelle/core/image.h>

namespace aq::reference {

enum class MorphologyOp { kErode, kDilate };
enum class MorphologyFootprint { kSquare, kDisc };
enum class MorphologyOrder { kPerChannel, kLuminance };

struct MorphologyParams {
  MorphologyOp op = MorphologyOp::kErode;
  int size = 3;  // odd window diameter
  MorphologyFootprint footprint = MorphologyFootprint::kSquare;
  MorphologyOrder order = MorphologyOrder::kPerChannel;
};

// True when offset (dx, dy) belongs to the footprint of odd diameter `size`: the square
// |dx|, |dy| <= size / 2, or the disc dx² + dy² <= (size / 2)² (size / 2 not rounded).
bool in_footprint(int dx, int dy, int size, MorphologyFootprint footprint);

// Rec.709 luminance order with ties broken by r, g, b, a: true when colour a precedes b.
bool luminance_less(const double a[4], const double b[4]);

// Erosion or dilation of a 4-channel image.
ImageF morphology(const ImageF& image, const MorphologyParams& params);

}  // namespace aq::reference
