// CPU reference of the `cel_light` node in double precision, written from the maths of
// plugins/cel_light/README.md: Lambert diffuse plus ambient from a directional light, then the
// colour taken to HSV (Smith 1978), its value quantised to N levels (in display space, the
// sRGB-encoded value, by default; with a floor that keeps a lit colour off black), and taken
// back to RGB.
// Shadow and caustics are left out here (shadow_reference.h covers shadows).
#pragma once

#include <aquarelle/core/image.h>

#include <array>

namespace aq::reference {

using Rgb = std::array<double, 3>;

struct Hsv {
  double h = 0;  // [0, 1)
  double s = 0;  // [0, 1]
  double v = 0;  // max(r, g, b), not clamped
};

Hsv rgb_to_hsv(const Rgb& rgb);
Rgb hsv_to_rgb(const Hsv& hsv);

// The sRGB transfer curve (IEC 61966-2-1), continued above 1 by its power law, and its inverse.
double srgb_encode(double v);
double srgb_decode(double e);

// levels >= 2: nearest of 0, 1/(N-1), 2/(N-1), ... (halves round up; above 1 the steps go on),
// of the sRGB-encoded value when `display` (then decoded back), else of v itself; with
// `floor`, v > 0 takes at least the first level above 0. levels = 1: one tone, 1 for any v > 0.
double quantize_value(double v, int levels, bool display = true, bool floor = true);

// The cel shading of one colour: through HSV, value quantised, back to RGB.
Rgb cel_shade(const Rgb& rgb, int levels, bool display = true, bool floor = true);

struct CelLightParams {
  Rgb light_direction{0, -1, 0};  // the direction light travels, unit
  Rgb light_color{1, 1, 1};
  Rgb ambient{0, 0, 0};
  int levels = 4;
  bool quantize = true;
  bool display = true;  // levels in display space (cel_light's `space`)
  bool floor = true;    // a lit colour keeps the first level above black (cel_light's `floor`)
  Rgb background{0.1, 0.3, 0.4};
};

// Per pixel of the gbuffer images (normal, albedo, id): the lit, cel-shaded colour, alpha 1.
ImageF cel_light(const ImageF& normal, const ImageF& albedo, const ImageF& id,
                 const CelLightParams& params);

}  // namespace aq::reference
