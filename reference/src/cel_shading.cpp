// CPU reference of cel_light (see cel_shading.h): the textbook HSV conversion, deliberately
// not the shader's shortcut (scaling rgb by v'/v), so the test checks that the shortcut is
// the same thing.
#include "aquarelle/reference/cel_shading.h"

#include <algorithm>
#include <cmath>

namespace aq::reference {

Hsv rgb_to_hsv(const Rgb& c) {
  double v = std::max({c[0], c[1], c[2]});
  double m = std::min({c[0], c[1], c[2]});
  double d = v - m;
  Hsv out;
  out.v = v;
  out.s = v > 0 ? d / v : 0;
  if (d > 0) {
    double h;
    if (v == c[0]) {
      h = std::fmod((c[1] - c[2]) / d + 6.0, 6.0);
    } else if (v == c[1]) {
      h = (c[2] - c[0]) / d + 2.0;
    } else {
      h = (c[0] - c[1]) / d + 4.0;
    }
    out.h = h / 6.0;
  }
  return out;
}

Rgb hsv_to_rgb(const Hsv& hsv) {
  double h = (hsv.h - std::floor(hsv.h)) * 6.0;
  int sector = static_cast<int>(std::floor(h)) % 6;
  double f = h - std::floor(h);
  double v = hsv.v, s = hsv.s;
  double p = v * (1 - s), q = v * (1 - s * f), t = v * (1 - s * (1 - f));
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

double srgb_encode(double v) {
  return v <= 0.0031308 ? 12.92 * v : 1.055 * std::pow(v, 1.0 / 2.4) - 0.055;
}

double srgb_decode(double e) {
  return e <= 0.04045 ? e / 12.92 : std::pow((e + 0.055) / 1.055, 2.4);
}

double quantize_value(double v, int levels, bool display, bool floor) {
  if (levels <= 1) return v > 0 ? 1.0 : 0.0;
  double steps = levels - 1;
  double k = std::floor((display ? srgb_encode(v) : v) * steps + 0.5);
  if (floor && v > 0) k = std::max(k, 1.0);
  return display ? srgb_decode(k / steps) : k / steps;
}

Rgb cel_shade(const Rgb& rgb, int levels, bool display, bool floor) {
  Hsv hsv = rgb_to_hsv(rgb);
  hsv.v = quantize_value(hsv.v, levels, display, floor);
  return hsv_to_rgb(hsv);
}

ImageF cel_light(const ImageF& normal, const ImageF& albedo, const ImageF& id,
                 const CelLightParams& params) {
  ImageF out(normal.width, normal.height, 4, 1.0f);
  for (int y = 0; y < normal.height; ++y) {
    for (int x = 0; x < normal.width; ++x) {
      Rgb color;
      if (!(id.at(x, y, 0) >= 0.5f)) {
        color = params.background;
      } else {
        Rgb n{normal.at(x, y, 0), normal.at(x, y, 1), normal.at(x, y, 2)};
        double len = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
        double ndl = 0;
        if (len > 1e-6) {
          for (int k = 0; k < 3; ++k) ndl -= n[k] / len * params.light_direction[k];
        }
        ndl = std::max(ndl, 0.0);
        for (int k = 0; k < 3; ++k) {
          double a = std::max(static_cast<double>(albedo.at(x, y, k)), 0.0);
          color[k] = a * (params.ambient[k] + params.light_color[k] * ndl);
        }
        if (params.quantize) color = cel_shade(color, params.levels, params.display, params.floor);
      }
      for (int k = 0; k < 3; ++k) out.at(x, y, k) = static_cast<float>(color[k]);
    }
  }
  return out;
}

}  // namespace aq::reference
