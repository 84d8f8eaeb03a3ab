// CPU reference of the `noise` texture node: see noise_texture_reference.h.
#include "aquarelle/reference/noise_texture_reference.h"

#include "aquarelle/reference/noise_reference.h"

#include <algorithm>
#include <cmath>

namespace aq::reference {

double cells_across_height(int scale, int width, int height) {
  return std::max(1.0, std::round(double(scale) * height / width));
}

double noise_value(const NoiseTextureParams& params, double px, double py, int width, int height) {
  const noise::Vec2 cells{double(params.scale), cells_across_height(params.scale, width, height)};
  const noise::Vec2 p{px / width * cells.x, py / height * cells.y};  // lattice units
  double v = 0.0;
  switch (params.type) {
    case NoiseType::kPerlin:
      v = noise::perlin2(p, cells, params.seed);
      return params.unit_range ? 0.5 + 0.5 * v : v;
    case NoiseType::kFbm:
      v = noise::fbm2(p, cells, params.octaves, params.seed);
      return params.unit_range ? 0.5 + 0.5 * v : v;
    case NoiseType::kGaussian: {
      const noise::Vec2 cell{double(noise::wrap_cell(int64_t(std::floor(p.x)), cells.x)),
                             double(noise::wrap_cell(int64_t(std::floor(p.y)), cells.y))};
      v = noise::gaussian_noise(cell, float(params.seed));
      return params.unit_range ? std::clamp(0.5 + v / 6.0, 0.0, 1.0) : v;
    }
    case NoiseType::kWorley:
      v = noise::worley2(p, cells, params.seed);
      return params.unit_range ? std::min(v, 1.0) : v;
  }
  return v;
}

ImageF noise_texture(const NoiseTextureParams& params, int width, int height) {
  ImageF out(width, height, 4, 1.0f);
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) {
      const float v = float(noise_value(params, x + 0.5, y + 0.5, width, height));
      for (int c = 0; c < 3; ++c) out.at(x, y, c) = v;
    }
  }
  return out;
}

}  // namespace aq::reference
