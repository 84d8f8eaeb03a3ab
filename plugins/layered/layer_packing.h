// Which RGBA channel of which pass range each layer of the layered node is painted in. Layers
// whose reach (blur, edges, composite) cannot meet share a channel: the passes of a range then
// serve any number of objects, and the range count follows how many layers pile up on one
// spot, not how many objects there are. Plain C++ (no GL) so tests can check it alone.
#pragma once

#include <vector>

#include "layer_table.h"

namespace layered {

// Two layers conflict when the gap between their pixel boxes is at most `gap` pixels (or
// always, when `gap` is negative: kernels wider than the image). Returns a channel per layer,
// in the order of `layers` (far to near): the lowest channel above every farther layer it
// conflicts with. So layers that paint a common pixel keep their far-to-near order, and
// layers sharing a channel never touch each other's pixels.
std::vector<int> assign_channels(const std::vector<Layer>& layers, int gap);

// The smallest gap at which two layers sharing a channel stay apart: the abstraction reach
// r_a on both sides, then the 3x3 edge detection and the edge blur reach r_e once more each.
int channel_gap(int reach_abstraction, int reach_edges);

}  // namespace layered
