// CPU reference of the `paper_relief` node: see paper_relief.h.
#include "aquarelle/reference/paper_relief.h"

#include <algorithm>
#include <cmath>

namespace aq::reference {

ImageF paper_relief(const ImageF& image, const ImageF& paper, const ImageF* mask,
                    const PaperReliefParams& p) {
  const bool masked = mask != nullptr && p.show > 0.0;
  if (p.relief <= 0.0 && !masked) return image;
  double l[3] = {p.light[0], p.light[1], std::max(p.light[2], 0.05)};
  const double ll = std::sqrt(l[0] * l[0] + l[1] * l[1] + l[2] * l[2]);
  for (double& v : l) v /= ll;
  auto height = [&](int x, int y) {
    return double(
        paper.at(std::clamp(x, 0, paper.width - 1), std::clamp(y, 0, paper.height - 1), 0));
  };
  ImageF out = image;
  for (int y = 0; y < image.height; ++y)
    for (int x = 0; x < image.width; ++x) {
      double base[3] = {image.at(x, y, 0), image.at(x, y, 1), image.at(x, y, 2)};
      if (masked) {
        const double m = mask->at(std::min(x * mask->width / image.width, mask->width - 1),
                                  std::min(y * mask->height / image.height, mask->height - 1), 0);
        const double show = std::isnan(m) ? 0.0 : std::clamp(p.show * m, 0.0, 1.0);
        if (show > 0.0)
          for (int c = 0; c < 3; ++c) base[c] += (p.paper_color[c] - base[c]) * show;
      }
      const int qx = x * paper.width / image.width, qy = y * paper.height / image.height;
      double dx = 0.5 * (height(qx + 1, qy) - height(qx - 1, qy));
      double dy = 0.5 * (height(qx, qy + 1) - height(qx, qy - 1));
      if (!std::isfinite(dx)) dx = 0.0;
      if (!std::isfinite(dy)) dy = 0.0;
      double n[3] = {-p.bump * dx, -p.bump * dy, 1.0};
      const double nl = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
      const double s = dx == 0.0 && dy == 0.0
                           ? 1.0
                           : std::max((n[0] * l[0] + n[1] * l[1] + n[2] * l[2]) / nl, 0.0) / l[2];
      for (int c = 0; c < 3; ++c)
        out.at(x, y, c) = static_cast<float>(base[c] * (1.0 + p.relief * (s - 1.0)));
    }
  return out;
}

}  // namespace aq::reference
