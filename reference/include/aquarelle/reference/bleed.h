// CPU reference of the `bleed` node in double precision (plugins/bleed/README.md): the gated
// separable bleeding blur, from its definition.
#pragma once

#include <aquarelle/core/image.h>

namespace aq::reference {

struct BleedParams {
  double sigma = 20.0;  // pixels
  double reach = 3.0;   // radius in sigmas
  double amount = 1.0;
  double depth_bias = 0.05;
};

// depth and id may be null (no depth test / one object).
ImageF bleed(const ImageF& image, const ImageF& control, const ImageF* depth, const ImageF* id,
             const BleedParams& params = {});

// The same gates and weights as one 2D kernel (every tap compared with the pixel directly), the
// operator the separable passes approximate; for measuring that approximation.
ImageF bleed_2d(const ImageF& image, const ImageF& control, const ImageF* depth, const ImageF* id,
                const BleedParams& params = {});

}  // namespace aq::reference
