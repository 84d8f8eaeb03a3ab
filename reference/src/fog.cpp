// CPU reference of the `fog` node: see fog.h.
#include "aquarelle/reference/fog.h"

#include <algorithm>
#include <cmath>

namespace aq::reference {

double fog_visibility(double z, bool emissive, const FogParams& params) {
  if (!std::isfinite(z) || z <= 0.0) return 0.0;
  const double k = emissive ? 1.0 - params.emission : 1.0;
  return std::exp(-k * std::pow(params.density * z, params.exponent));
}

ImageF fog(const ImageF& image, const ImageF& depth, const ImageF* id, const FogParams& params) {
  ImageF out = image;
  for (int y = 0; y < image.height; ++y)
    for (int x = 0; x < image.width; ++x) {
      bool emissive = false;
      if (id != nullptr) {
        const double object = std::round(id->at(x, y, 0));
        emissive = std::any_of(params.emissive_ids.begin(), params.emissive_ids.end(),
                               [&](int e) { return e == object; });
      }
      const double v = fog_visibility(depth.at(x, y, 0), emissive, params);
      for (int c = 0; c < 3; ++c) {
        out.at(x, y, c) =
            static_cast<float>(params.color[c] + (image.at(x, y, c) - params.color[c]) * v);
      }
    }
  return out;
}

}  // namespace aq::reference
