// CPU reference of the `edge_darkening` node: see edge_darkening.h.
#include "aquarelle/reference/edge_darkening.h"

#include "aquarelle/reference/blur.h"

#include <algorithm>
#include <cmath>

namespace aq::reference {

ImageF blur_difference_darkening(const ImageF& image, const ImageF* source, const ImageF* control,
                                 const EdgeDarkeningParams& p) {
  if (!(p.sigma > 0.0) || !(p.strength > 0.0)) return image;
  const ImageF& s = source != nullptr ? *source : image;
  const ImageF blurred = gaussian_blur(s, p.sigma);
  ImageF out = image;
  for (int y = 0; y < image.height; ++y)
    for (int x = 0; x < image.width; ++x) {
      const int sx = std::min(x * s.width / image.width, s.width - 1);
      const int sy = std::min(y * s.height / image.height, s.height - 1);
      double d = 0.0, scale = 1.0;
      for (int c = 0; c < 3; ++c) {
        d = std::max(d, std::abs(double(blurred.at(sx, sy, c)) - s.at(sx, sy, c)));
        scale = std::max(scale, std::abs(double(s.at(sx, sy, c))));
      }
      if (!(d > p.dead_zone * scale) || !std::isfinite(d)) d = 0.0;
      double k = p.strength;
      if (control != nullptr) {
        const int cx = std::min(x * control->width / image.width, control->width - 1);
        const int cy = std::min(y * control->height / image.height, control->height - 1);
        // The grazing angle through the node's 3x3 tent (1, 2, 1) ⊗ (1, 2, 1) / 16, clamped.
        double grazing = 0.0;
        for (int j = -1; j <= 1; ++j)
          for (int i = -1; i <= 1; ++i) {
            const int gx = std::clamp(cx + i, 0, control->width - 1);
            const int gy = std::clamp(cy + j, 0, control->height - 1);
            grazing += (i == 0 ? 2.0 : 1.0) * (j == 0 ? 2.0 : 1.0) / 16.0 * control->at(gx, gy, 2);
          }
        k *= std::max(control->at(cx, cy, 1) + p.grazing * grazing, 0.0);
        if (!std::isfinite(k)) k = 0.0;
      }
      double e = k * d;
      if (p.max_exponent > 0.0) e = p.max_exponent * (1.0 - std::exp(-e / p.max_exponent));
      if (!(e > 0.0)) continue;
      for (int c = 0; c < 3; ++c) {
        const double v = image.at(x, y, c);
        if (v > 0.0 && v < 1.0) out.at(x, y, c) = static_cast<float>(std::pow(v, 1.0 + e));
      }
    }
  return out;
}

}  // namespace aq::reference
