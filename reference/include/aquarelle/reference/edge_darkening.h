// CPU reference of the `edge_darkening` node in double precision (plugins/edge_darkening/
// README.md): d = max_rgb |G_σ * S − S|, k = strength (· (g + grazing · tent3x3(b)) with a
// control map), e = e_max (1 − exp(−k d / e_max)) (e_max 0: e = k d),
// out_c = C_c · min(C_c, 1)^e for C_c > 0 (C^(1 + e) in [0, 1]); d under the dead zone is 0.
#pragma once

#include <aquarelle/core/image.h>

namespace aq::reference {

struct EdgeDarkeningParams {
  double sigma = 3.0;
  double strength = 4.0;
  double grazing = 1.0;
  double dead_zone = 1e-5;
  double max_exponent = 1.0;
};

// source and control may be null (the image itself / k = strength).
ImageF blur_difference_darkening(const ImageF& image, const ImageF* source, const ImageF* control,
                                 const EdgeDarkeningParams& params = {});

}  // namespace aq::reference
