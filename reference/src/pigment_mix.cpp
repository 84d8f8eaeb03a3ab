// CPU references of subtractive colour mixing: see pigment_mix.h.
#include "aquarelle/reference/pigment_mix.h"

#include <algorithm>
#include <cmath>

namespace aq::reference {

namespace {
constexpr double kEps = 1.0e-4;
double clamp01(double v) {
  return v >= 0.0 ? std::min(v, 1.0) : 0.0;
}
}  // namespace

Rgb sanitize(const Rgb& c) {
  return {clamp01(c[0]), clamp01(c[1]), clamp01(c[2])};
}

std::array<double, 4> rgb_to_cmyk(const Rgb& c) {
  const double k = 1.0 - std::max({c[0], c[1], c[2]});
  const double d = 1.0 - k;
  if (!(d > 0.0)) return {0.0, 0.0, 0.0, k};
  return {(1.0 - c[0] - k) / d, (1.0 - c[1] - k) / d, (1.0 - c[2] - k) / d, k};
}

Rgb cmyk_to_rgb(const std::array<double, 4>& cmyk) {
  return {(1.0 - cmyk[0]) * (1.0 - cmyk[3]), (1.0 - cmyk[1]) * (1.0 - cmyk[3]),
          (1.0 - cmyk[2]) * (1.0 - cmyk[3])};
}

// Curtis et al. 1997, sec. 4.3, solved for a unit layer that reflects rw over white and rb
// over black: a = ½ (rw + (rb − rw + 1) / rb), b = √(a² − 1),
// S = arccoth((b² − (a − rw)(a − 1)) / (b (1 − rw))) / b, K = S (a − 1).
KmPigment km_pigment(double rw, double rb) {
  rw = std::clamp(rw, 2.0 * kEps, 1.0 - kEps);
  rb = std::clamp(rb, kEps, rw - kEps);
  const double a = 0.5 * (rw + (rb - rw + 1.0) / rb);
  const double b = std::sqrt(std::max(a * a - 1.0, 1.0e-12));
  const double arg = std::max((b * b - (a - rw) * (a - 1.0)) / (b * (1.0 - rw)), 1.0 + 1.0e-6);
  const double s = 0.5 * std::log((arg + 1.0) / (arg - 1.0)) / b;  // arccoth(arg) / b
  return {s * (a - 1.0), s};
}

// c = a sinh(bSx) + b cosh(bSx), R = sinh(bSx) / c, T = b / c with a = 1 + K/S, b = √(a² − 1).
std::array<double, 2> km_layer(const KmPigment& p, double x) {
  if (!(p.s > 0.0) || !(x > 0.0)) return {0.0, 1.0};
  const double a = 1.0 + p.k / p.s;
  const double b = std::sqrt(std::max(a * a - 1.0, 1.0e-12));
  const double bsx = std::min(b * p.s * x, 40.0);
  const double c = a * std::sinh(bsx) + b * std::cosh(bsx);
  return {std::sinh(bsx) / c, b / c};
}

double km_over(const std::array<double, 2>& layer, double r2) {
  return layer[0] + layer[1] * layer[1] * r2 / (1.0 - layer[0] * r2);
}

Rgb mix(const Rgb& a_in, const Rgb& b_in, double t, MixMode mode) {
  const Rgb a = sanitize(a_in), b = sanitize(b_in);
  Rgb out{};
  switch (mode) {
    case MixMode::kRgb:
      for (int i = 0; i < 3; ++i) out[i] = a[i] + (b[i] - a[i]) * t;
      return out;
    case MixMode::kCmyk: {
      const auto ca = rgb_to_cmyk(a), cb = rgb_to_cmyk(b);
      std::array<double, 4> m{};
      for (int i = 0; i < 4; ++i) m[i] = ca[i] + (cb[i] - ca[i]) * t;
      return cmyk_to_rgb(m);
    }
    case MixMode::kKubelkaMunk:
      for (int i = 0; i < 3; ++i) {
        const KmPigment pa = km_pigment(a[i], kKmBlackRatio * a[i]);
        const KmPigment pb = km_pigment(b[i], kKmBlackRatio * b[i]);
        const KmPigment m{pa.k + (pb.k - pa.k) * t, pa.s + (pb.s - pa.s) * t};
        out[i] = km_over(km_layer(m, 1.0), 1.0);
      }
      return sanitize(out);
  }
  return out;
}

Rgb km_glaze(const Rgb& under_in, const Rgb& colour_in, double thickness) {
  const Rgb under = sanitize(under_in), colour = sanitize(colour_in);
  Rgb out{};
  for (int i = 0; i < 3; ++i) {
    const KmPigment p = km_pigment(colour[i], kKmBlackRatio * colour[i]);
    out[i] = km_over(km_layer(p, thickness), under[i]);
  }
  return sanitize(out);
}

ImageF pigment_mix(const ImageF& a, const ImageF& b, double factor, MixMode mode) {
  ImageF out = a;
  for (int y = 0; y < a.height; ++y)
    for (int x = 0; x < a.width; ++x) {
      const Rgb ca{a.at(x, y, 0), a.at(x, y, 1), a.at(x, y, 2)};
      const Rgb cb{b.at(x, y, 0), b.at(x, y, 1), b.at(x, y, 2)};
      const double alpha = b.channels > 3 ? b.at(x, y, 3) : 1.0;
      double t = factor * (alpha >= 0.0 ? std::min(alpha, 1.0) : 0.0);
      const Rgb m = mix(ca, cb, t, mode);
      for (int c = 0; c < 3; ++c) out.at(x, y, c) = static_cast<float>(m[c]);
      if (out.channels > 3) {
        const float av = a.at(x, y, 3);
        out.at(x, y, 3) = std::isfinite(av) ? av : 0.0f;
      }
    }
  return out;
}

}  // namespace aq::reference
