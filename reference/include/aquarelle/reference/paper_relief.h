// CPU reference of the `paper_relief` node in double precision (plugins/paper_relief/README.md):
// base = mix(C, paper_colour, clamp(show · m, 0, 1)); N = normalize(−bump h_x, −bump h_y, 1) from
// central differences of the paper height (nearest texel under the pixel, clamped borders);
// s = max(N·L, 0) / L_z; out = base · (1 + relief (s − 1)); alpha kept.
#pragma once

#include <aquarelle/core/image.h>

#include <array>

namespace aq::reference {

struct PaperReliefParams {
  std::array<double, 3> light{-0.5, 0.5, 0.7};  // normalised inside (z at least 0.05)
  double bump = 4.0;
  double relief = 1.0;
  std::array<double, 3> paper_color{0.96, 0.93, 0.85};
  double show = 1.0;
};

ImageF paper_relief(const ImageF& image, const ImageF& paper, const ImageF* mask,
                    const PaperReliefParams& params = {});

}  // namespace aq::reference
