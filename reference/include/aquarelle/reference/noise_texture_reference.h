// CPU reference of the `noise` texture node in double precision (plugins/noise/README.md), for
// the tests and `aquarelle bench`.
#pragma once

#include <aquarelle/core/image.h>

#include <cstdint>

namespace aq::reference {

enum class NoiseType { kPerlin = 0, kFbm = 1, kGaussian = 2, kWorley = 3 };

struct NoiseTextureParams {
  NoiseType type = NoiseType::kFbm;
  int scale = 8;  // lattice cells across the width
  int octaves = 5;
  uint32_t seed = 0;
  bool unit_range = true;
};

// Whole number of square-ish cells across the height for `scale` cells across the width.
double cells_across_height(int scale, int width, int height);

// The node's value at pixel coordinates (px, py) of a width x height texture (pixel centres
// are at x + 0.5); defined everywhere, also outside the texture, where it repeats.
double noise_value(const NoiseTextureParams& params, double px, double py, int width, int height);

ImageF noise_texture(const NoiseTextureParams& params, int width, int height);

}  // namespace aq::reference
