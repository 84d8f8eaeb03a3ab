// CPU reference of the `fog` node in double precision, from the maths of plugins/fog/README.md:
// visibility = exp(-k (density·z)^exponent), k = 1 - emission on emissive objects, else 1;
// out = water + (colour - water)·visibility; z <= 0 or not finite is background (visibility 0).
#pragma once

#include <aquarelle/core/image.h>

#include <array>
#include <vector>

namespace aq::reference {

struct FogParams {
  std::array<double, 3> color{0.0, 0.07, 0.1};
  double density = 0.04;
  double exponent = 1.0;
  std::vector<int> emissive_ids;
  double emission = 0.8;
};

// Visibility in [0, 1] for view depth z, emissive or not.
double fog_visibility(double z, bool emissive, const FogParams& params);

// `depth` and `id` (channel 0) have the image's size; `id` may be null.
ImageF fog(const ImageF& image, const ImageF& depth, const ImageF* id, const FogParams& params);

}  // namespace aq::reference
