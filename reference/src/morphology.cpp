// CPU reference for erosion and dilation: the direct 2D definition over the whole footprint, in
// double precision, so that it checks the shader's row/column decomposition as well.
#include "aquarelle/reference/morphology.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

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

int region_label(double r, double g, double b) {
  auto byte = [](double c) {
    return static_cast<uint32_t>(std::lround(std::clamp(c, 0.0, 1.0) * 255.0));
  };
  uint32_t h = byte(r) | byte(g) << 8 | byte(b) << 16;
  h ^= h >> 15;
  h *= 0x2C1B3C6Du;
  h ^= h >> 12;
  h *= 0x297A2D39u;
  h ^= h >> 15;
  return static_cast<int>(h >> 24);
}

ImageF confined_morphology(const ImageF& image, const ImageF& regions,
                           const MorphologyParams& params, MorphologyAxes axes) {
  const int w = image.width, h = image.height;
  std::vector<int> labels(static_cast<size_t>(w) * h);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x)
      labels[static_cast<size_t>(y) * w + x] =
          region_label(regions.at(x, y, 0), regions.at(x, y, 1), regions.at(x, y, 2));
  auto label = [&](int x, int y) {
    return labels[static_cast<size_t>(std::clamp(y, 0, h - 1)) * w + std::clamp(x, 0, w - 1)];
  };
  ImageF out(w, h, 4, 1.0f);
  const int radius = params.size / 2;
  const bool dilate = params.op == MorphologyOp::kDilate;
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      const int own = label(x, y);
      double best[3] = {0, 0, 0};
      bool first = true;
      for (int dy = -radius; dy <= radius; ++dy) {
        for (int dx = -radius; dx <= radius; ++dx) {
          if (!in_footprint(dx, dy, params.size, params.footprint)) continue;
          const bool rows_first = axes == MorphologyAxes::kRowsFirst;
          if (label(x + dx, y + dy) != own ||
              label(rows_first ? x : x + dx, rows_first ? y + dy : y) != own)
            continue;
          const int sx = std::clamp(x + dx, 0, w - 1), sy = std::clamp(y + dy, 0, h - 1);
          double candidate[4] = {0, 0, 0, static_cast<double>(own)};
          for (int c = 0; c < 3; ++c) candidate[c] = image.at(sx, sy, c);
          if (first) {
            std::copy(candidate, candidate + 3, best);
            first = false;
          } else if (params.order == MorphologyOrder::kLuminance) {
            double current[4] = {best[0], best[1], best[2], static_cast<double>(own)};
            const bool replace =
                dilate ? luminance_less(current, candidate) : luminance_less(candidate, current);
            if (replace) std::copy(candidate, candidate + 3, best);
          } else {
            for (int c = 0; c < 3; ++c)
              best[c] = dilate ? std::max(best[c], candidate[c]) : std::min(best[c], candidate[c]);
          }
        }
      }
      for (int c = 0; c < 3; ++c) out.at(x, y, c) = static_cast<float>(best[c]);
    }
  }
  return out;
}

}  // namespace aq::reference
