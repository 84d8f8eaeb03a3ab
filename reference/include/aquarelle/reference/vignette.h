// CPU reference of the `vignette` node in double precision, written from the maths of
// plugins/vignette/README.md (aspect-correct radial ramp), for the tests and `aquarelle bench`.
#pragma once

#include <aquarelle/core/image.h>

namespace aq::reference {

struct VignetteParams {
  double radius = 0.45;
  double strength = 0.7;
  double softness = 1.0;
};

// Darkening factor (1 - strength * t) at pixel (x, y) of a width x height image.
double vignette_factor(int x, int y, int width, int height, const VignetteParams& params);

ImageF vignette(const ImageF& image, const VignetteParams& params = {});

}  // namespace aq::reference
