// CPU reference of the `vignette` node: see vignette.h.
#include "aquarelle/reference/vignette.h"

#include <algorithm>
#include <cmath>

namespace aq::reference {

double vignette_factor(int x, int y, int width, int height, const VignetteParams& params) {
  const double shorter = std::min(width, height);
  const double dx = (x + 0.5 - 0.5 * width) / shorter;
  const double dy = (y + 0.5 - 0.5 * height) / shorter;
  const double d = std::sqrt(dx * dx + dy * dy);
  const double corner = 0.5 * std::sqrt(double(width) * width + double(height) * height) / shorter;
  if (d <= params.radius) return 1.0;
  const double ramp = params.softness * (corner - params.radius);
  const double t = ramp > 0.0 ? std::min((d - params.radius) / ramp, 1.0) : 1.0;
  return 1.0 - params.strength * t;
}

ImageF vignette(const ImageF& image, const VignetteParams& params) {
  ImageF out = image;
  for (int y = 0; y < image.height; ++y) {
    for (int x = 0; x < image.width; ++x) {
      const double f = vignette_factor(x, y, image.width, image.height, params);
      for (int c = 0; c < std::min(image.channels, 3); ++c) {
        out.at(x, y, c) = static_cast<float>(image.at(x, y, c) * f);
      }
    }
  }
  return out;
}

}  // namespace aq::reference
