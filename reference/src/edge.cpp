// CPU reference of edge darkening: kernel response, smoothstep, HSV value scaling.
#include "aquarelle/reference/edge.h"

#include "aquarelle/reference/cel_shading.h"

#include <algorithm>
#include <array>
#include <cmath>

namespace aq::reference {
namespace {

// HSV conversions are the cel-shading reference's (Smith's hexcone, V = max(r, g, b)).

double smoothstep(double edge0, double edge1, double x) {
  const double t = std::clamp((x - edge0) / (edge1 - edge0), 0.0, 1.0);
  return t * t * (3.0 - 2.0 * t);
}

}  // namespace

double edge_response(const ImageF& source, int x, int y, EdgeKernel kernel) {
  auto at = [&](int dx, int dy, int c) {
    const int sx = std::clamp(x + dx, 0, source.width - 1);
    const int sy = std::clamp(y + dy, 0, source.height - 1);
    return static_cast<double>(source.at(sx, sy, c));
  };
  double response = 0.0;
  for (int c = 0; c < 3; ++c) {
    double r = 0.0;
    if (kernel == EdgeKernel::kLaplacian) {
      for (int dy = -1; dy <= 1; ++dy) {
        for (int dx = -1; dx <= 1; ++dx) r += (dx == 0 && dy == 0 ? -8.0 : 1.0) * at(dx, dy, c);
      }
      r = std::abs(r);
    } else {
      const double gx = at(1, -1, c) + 2 * at(1, 0, c) + at(1, 1, c) - at(-1, -1, c) -
                        2 * at(-1, 0, c) - at(-1, 1, c);
      const double gy = at(-1, 1, c) + 2 * at(0, 1, c) + at(1, 1, c) - at(-1, -1, c) -
                        2 * at(0, -1, c) - at(1, -1, c);
      r = std::sqrt(gx * gx + gy * gy);
    }
    if (std::isnan(r)) r = 0.0;
    response = std::max(response, r);
  }
  return response;
}

ImageF edge_darkening(const ImageF& image, const ImageF* source, const EdgeParams& params) {
  const ImageF& detect = source != nullptr ? *source : image;
  ImageF out = image;
  for (int y = 0; y < image.height; ++y) {
    for (int x = 0; x < image.width; ++x) {
      const int sx = static_cast<int>(std::floor((x + 0.5) / image.width * detect.width));
      const int sy = static_cast<int>(std::floor((y + 0.5) / image.height * detect.height));
      const double edge = smoothstep(params.threshold, params.threshold + params.softness,
                                     edge_response(detect, sx, sy, params.kernel));
      Hsv hsv = rgb_to_hsv({image.at(x, y, 0), image.at(x, y, 1), image.at(x, y, 2)});
      hsv.v *= 1.0 + (params.factor - 1.0) * edge;
      const Rgb rgb = hsv_to_rgb(hsv);
      for (int c = 0; c < 3; ++c) out.at(x, y, c) = static_cast<float>(rgb[c]);
    }
  }
  return out;
}

}  // namespace aq::reference
