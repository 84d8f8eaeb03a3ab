// CPU reference of the `dilution` node: see dilution.h.
#include "aquarelle/reference/dilution.h"

#include "aquarelle/reference/noise_reference.h"

#include <algorithm>
#include <cmath>

namespace aq::reference {

DilutionResult dilution(const ImageF& albedo, const ImageF& normal, const ImageF* anchor,
                        const DilutionParams& p) {
  DilutionResult r{albedo, ImageF(albedo.width, albedo.height, 4, 0.0f)};
  for (int y = 0; y < albedo.height; ++y)
    for (int x = 0; x < albedo.width; ++x) {
      r.image.at(x, y, 3) = 1.0f;  // the painting is opaque
      if (!(albedo.at(x, y, 3) > 0.0f)) continue;
      double d = 0.0;
      for (int c = 0; c < 3; ++c) d += double(normal.at(x, y, c)) * p.to_light[c];
      double lit = std::clamp((d + p.diffuse_area - 1.0) / p.diffuse_area, 0.0, 1.0);
      if (std::isnan(lit)) lit = 0.0;
      double turbulence = 0.0;
      if (anchor != nullptr && p.turbulence > 0.0) {
        const noise::Vec3 q{anchor->at(x, y, 0) * p.scale, anchor->at(x, y, 1) * p.scale,
                            anchor->at(x, y, 2) * p.scale};
        turbulence = p.turbulence * (p.turbulence_bend > 0.0
                                         ? noise::fbm3_bent(q, p.octaves, p.turbulence_bend)
                                         : noise::fbm3(q, p.octaves));
        if (!std::isfinite(turbulence)) turbulence = 0.0;
      }
      const double dil = std::clamp(p.dilution * lit * (1.0 + turbulence), 0.0, 1.0);
      const double lighter = std::clamp(p.cangiante * lit, 0.0, 1.0);
      for (int c = 0; c < 3; ++c) {
        const double a = albedo.at(x, y, c) + lighter;
        r.image.at(x, y, c) =
            static_cast<float>((a + (p.paper[c] - a) * dil) * (1.0 - p.shade * (1.0 - lit)));
        r.dilution.at(x, y, c) = static_cast<float>(dil);
      }
      r.dilution.at(x, y, 3) = 1.0f;
    }
  return r;
}

}  // namespace aq::reference
