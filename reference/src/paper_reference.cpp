// CPU reference of the `paper` texture node: see paper_reference.h.
#include "aquarelle/reference/paper_reference.h"

#include "aquarelle/reference/noise_reference.h"
#include "aquarelle/reference/noise_texture_reference.h"

#include <algorithm>
#include <cmath>

namespace aq::reference {

namespace {
constexpr uint32_t kFiberSeedSalt = 0x68BC21EBu;
}

double paper_height(double u, double v, int width, int height, const PaperParams& params) {
  const noise::Vec2 grain_cells{double(params.grain_scale),
                                cells_across_height(params.grain_scale, width, height)};
  const noise::Vec2 fiber_cells{double(params.fiber_scale),
                                cells_across_height(params.fiber_scale, width, height)};
  // Grain: bumps centred on the Worley feature points (1 - F1, cut at distance 1).
  const double grain = 1.0 - std::min(noise::worley2({u * grain_cells.x, v * grain_cells.y},
                                                     grain_cells, params.seed),
                                      1.0);
  // Fibres and cloudiness: fBm on its own lattice, mapped to [0,1].
  const double fibers = 0.5 + 0.5 * noise::fbm2({u * fiber_cells.x, v * fiber_cells.y}, fiber_cells,
                                                params.octaves, params.seed ^ kFiberSeedSalt);
  const double relief = (1.0 - params.fiber_weight) * grain + params.fiber_weight * fibers - 0.5;
  return 0.5 + params.roughness * relief;
}

ImageF paper_texture(const PaperParams& params, int width, int height) {
  ImageF out(width, height, 4, 1.0f);
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) {
      const double h = paper_height((x + 0.5) / width, (y + 0.5) / height, width, height, params);
      for (int c = 0; c < 3; ++c) out.at(x, y, c) = float(h);
    }
  }
  return out;
}

}  // namespace aq::reference
