// CPU references of subtractive colour mixing in double precision, written from the maths in
// plugins/pigment_mix/README.md: the additive lerp, the seed's (004) CMYK interpolation and
// Kubelka–Munk two-constant mixing and glazing (Curtis et al. 1997, sec. 4). Used by the
// pigment_mix and layered tests and by `aquarelle bench` (the colour chart).
#pragma once

#include <aquarelle/core/image.h>

#include <array>

namespace aq::reference {

using Rgb = std::array<double, 3>;

enum class MixMode { kRgb = 0, kCmyk = 1, kKubelkaMunk = 2 };

// The colour chart of docs/pigment_chart.png (scripts/pigment_chart.cpp) and of the pigment
// sweep of `aquarelle bench`: seven pigment pairs, each a contrast the mixing modes disagree on.
struct PigmentPair {
  const char* name;
  Rgb a, b;
};
inline constexpr PigmentPair kPigmentChart[] = {{"blue+yellow", {0.1, 0.2, 0.8}, {0.9, 0.8, 0.1}},
                                                {"red+blue", {0.8, 0.1, 0.1}, {0.1, 0.2, 0.8}},
                                                {"red+yellow", {0.8, 0.1, 0.1}, {0.9, 0.8, 0.1}},
                                                {"cyan+magenta", {0.1, 0.7, 0.8}, {0.8, 0.1, 0.6}},
                                                {"blue+white", {0.1, 0.2, 0.8}, {1.0, 1.0, 1.0}},
                                                {"red+black", {0.8, 0.1, 0.1}, {0.0, 0.0, 0.0}},
                                                {"green+itself", {0.2, 0.6, 0.2}, {0.2, 0.6, 0.2}}};

// Over black a unit layer of a pigment reflects this fraction of what it reflects over white.
constexpr double kKmBlackRatio = 0.2;

// Components clamped to [0, 1], NaN to 0.
Rgb sanitize(const Rgb& c);

std::array<double, 4> rgb_to_cmyk(const Rgb& c);
Rgb cmyk_to_rgb(const std::array<double, 4>& cmyk);

struct KmPigment {
  double k = 0.0;  // absorption per unit thickness
  double s = 0.0;  // scattering per unit thickness
};
// K and S of the pigment whose unit layer reflects rw over white and rb over black.
KmPigment km_pigment(double rw, double rb);
// Reflectance R and transmittance T of a layer of thickness x.
std::array<double, 2> km_layer(const KmPigment& p, double x);
// The layer (R, T) over a background reflecting r2.
double km_over(const std::array<double, 2>& layer, double r2);

Rgb mix(const Rgb& a, const Rgb& b, double t, MixMode mode);
// `thickness` of the pigment that looks like `colour` at unit thickness on white, over `under`.
Rgb km_glaze(const Rgb& under, const Rgb& colour, double thickness);

// The pigment_mix node: per pixel mix(a.rgb, b.rgb, factor · b.a) in `mode`; alpha from a.
ImageF pigment_mix(const ImageF& a, const ImageF& b, double factor, MixMode mode);

}  // namespace aq::reference
