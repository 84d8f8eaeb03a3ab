// CPU reference of edge darkening: kernel response, smoothstep, HSV value scaling.
#include "reference/edge.h"

#include <algorithm>
#include <array>
#include <cmath>

namespace aq::reference {
namespace {

using Rgb = std::array<double, 3>;

// Smith's hexcone HSV with V = max(r, g, b); hue in [0, 6).
Rgb to_hsv(const Rgb& c) {
  const double v = std::max({c[0], c[1], c[2]});
  const double m = std::min({c[0], c[1], c[2]});
  const double d = v - m;
  const double s = v > 0.0 ? d / v : 0.0;
  double h = 0.0;
  if (d > 0.0) {
    if (v == c[0]) {
      h = std::fmod((c[1] - c[2]) / d + 6.0, 6.0);
    } else if (v == c[1]) {
      h = 2.0 + (c[2] - c[0]) / d;
    } else {
      h = 4.0 + (c[0] - c[1]) / d;
    }
  }
  return {h, s, v};
}

Rgb from_hsv(const Rgb& hsv) {
  const double h = hsv[0];
  const double s = hsv[1];
  const double v = hsv[2];
  const int sector = static_cast<int>(std::floor(h)) % 6;
  const double f = h - std::floor(h);
  const double p = v * (1.0 - s);
  const double q = v * (1.0 - s * f);
  const double t = v * (1.0 - s * (1.0 - f));
  switch (sector) {
    case 0:
      return {v, t, p};
    case 1:
      return {q, v, p};
    case 2:
      return {p, v, t};
    case 3:
      return {p, q, v};
    case 4:
      return {t, p, v};
    default:
      return {v, p, q};
  }
}

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
      Rgb hsv = to_hsv({image.at(x, y, 0), image.at(x, y, 1), image.at(x, y, 2)});
      hsv[2] *= 1.0 + (params.factor - 1.0) * edge;
      const Rgb rgb = from_hsv(hsv);
      for (int c = 0; c < 3; ++c) out.at(x, y, c) = static_cast<float>(rgb[c]);
    }
  }
  return out;
}

}  // namespace aq::reference
