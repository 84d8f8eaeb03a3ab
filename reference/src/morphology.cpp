// CPU reference for erosion and dilation: the direct 2D definition over the whole footprint, in
// double precision, so that it checks the shader's row/column decomposition as well.
#include "aquarelle/reference/morphology.h"

#include <algorithm>
#include <cmath>

namespace aq::reference {

bool in_footprint(int dx, int dy, int size, MorphologyFootprint footprint) {
  const double half = size / 2.0;
  if (footprint == MorphologyFootprint::kSquare) {
    return std::abs(dx) <= size / 2 && std::abs(dy) <= size / 2;
  }
  return static_cast<double>(dx) * dx + static_cast<double>(dy) * dy <= half * half;
}

bool luminance_less(const double a[4], const double b[4]) {
  const double la = 0.2126 * a[0] + 0.7152 * a[1] + 0.0722 * a[2];
  const double lb = 0.2126 * b[0] + 0.7152 * b[1] + 0.0722 * b[2];
  if (la != lb) return la < lb;
  for (int c = 0; c < 4; ++c) {
    if (a[c] != b[c]) return a[c] < b[c];
  }
  return false;
}

ImageF morphology(const ImageF& image, const MorphologyParams& params) {
  ImageF out(image.width, image.height, 4);
  const int radius = params.size / 2;
  const bool dilate = params.op == MorphologyOp::kDilate;
  for (int y = 0; y < image.height; ++y) {
    for (int x = 0; x < image.width; ++x) {
      double best[4] = {0, 0, 0, 0};
      bool first = true;
      for (int dy = -radius; dy <= radius; ++dy) {
        for (int dx = -radius; dx <= radius; ++dx) {
          if (!in_footprint(dx, dy, params.size, params.footprint)) continue;
          const int sx = std::clamp(x + dx, 0, image.width - 1);
          const int sy = std::clamp(y + dy, 0, image.height - 1);
          double candidate[4];
          for (int c = 0; c < 4; ++c) candidate[c] = c < image.channels ? image.at(sx, sy, c) : 1.0;
          if (first) {
            std::copy(candidate, candidate + 4, best);
            first = false;
          } else if (params.order == MorphologyOrder::kLuminance) {
            const bool replace =
                dilate ? luminance_less(best, candidate) : luminance_less(candidate, best);
            if (replace) std::copy(candidate, candidate + 4, best);
          } else {
            for (int c = 0; c < 4; ++c) {
              best[c] = dilate ? std::max(best[c], candidate[c]) : std::min(best[c], candidate[c]);
            }
          }
        }
      }
      for (int c = 0; c < 4; ++c) out.at(x, y, c) = static_cast<float>(best[c]);
    }
  }
  return out;
}

}  // namespace aq::reference
