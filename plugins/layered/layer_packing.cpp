// The layered node's channel packing: see layer_packing.h.
#include "layer_packing.h"

#include <algorithm>

namespace layered {

namespace {

bool conflict(const Layer& a, const Layer& b, int gap) {
  if (gap < 0) return true;
  const int dx = std::max(a.x0, b.x0) - std::min(a.x1, b.x1);
  const int dy = std::max(a.y0, b.y0) - std::min(a.y1, b.y1);
  return dx <= gap && dy <= gap;
}

}  // namespace

int channel_gap(int reach_abstraction, int reach_edges) {
  return 2 * reach_abstraction + 2 * reach_edges + 2;
}

std::vector<int> assign_channels(const std::vector<Layer>& layers, int gap) {
  std::vector<int> channel(layers.size(), 0);
  for (size_t j = 0; j < layers.size(); ++j) {
    int c = 0;
    for (size_t i = 0; i < j; ++i) {
      if (channel[i] >= c && conflict(layers[i], layers[j], gap)) c = channel[i] + 1;
    }
    channel[j] = c;
  }
  return channel;
}

}  // namespace layered
