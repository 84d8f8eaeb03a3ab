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

// The 8-bit label of a region colour (the node's `regions` input): its three bytes
// round(255 · clamp(c, 0, 1)) packed as r | g << 8 | b << 16 and hashed (an integer mixer), top
// byte. Equal colours share a label; two different colours share one with probability 1/256.
int region_label(double r, double g, double b);

// Which axis a confined node's window takes first: x (its rows pass first, as a node on its own
// runs) or y (a node that runs the columns pass its writer handed on first, such as the
// flagship's dilate between two erodes: `render --plan`, AQ_PORT_DEFER_AXIS).
enum class MorphologyAxes { kRowsFirst, kColumnsFirst };

// Erosion or dilation confined to regions (the node with `regions` connected): pixel q of the
// footprint around p counts only when q, p and the corner between them share p's region label,
// the corner being (p.x, q.y) when rows come first (q's row extreme is taken in q's row at
// that corner, then the column pass at p takes the rows of p's region) and (q.x, p.y) when
// columns come first. Coordinates clamp to the image. So no colour crosses from one region into
// another, and a region thinner than the window keeps its own colours. Alpha of the result is
// 1 (the labels ride in alpha inside the node; the image's alpha is not filtered).
ImageF confined_morphology(const ImageF& image, const ImageF& regions,
                           const MorphologyParams& params,
                           MorphologyAxes axes = MorphologyAxes::kRowsFirst);

}  // namespace aq::reference
