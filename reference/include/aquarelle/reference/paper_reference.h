// CPU reference of the `paper` texture node in double precision (plugins/paper/README.md), for
// the tests and `aquarelle bench`.
#pragma once

#include <aquarelle/core/image.h>

#include <cstdint>

namespace aq::reference {

struct PaperParams {
  int grain_scale = 48;  // Worley cells across the width
  int fiber_scale = 6;   // fBm lattice cells across the width
  int octaves = 5;
  double fiber_weight = 0.35;
  double roughness = 1.0;
  uint32_t seed = 0;
};

// Height at texture position (u, v) in [0,1)^2 of a width x height texture.
double paper_height(double u, double v, int width, int height, const PaperParams& params);

ImageF paper_texture(const PaperParams& params, int width, int height);

}  // namespace aq::reference
