// CPU reference of the screen-space `tremor` node in double precision (plugins/tremor/README.md):
// out(p) = bilinear(image, (p + ½ + offset) / size), offset = amplitude · m ·
// (perlin3(q, φ), perlin3(q + (7.31, 3.17), φ + 11.7)), q = (p + ½) / wavelength, φ = t · speed,
// m = control alpha (1 without a control map); m = 0 reads the texel itself.
#pragma once

#include <aquarelle/core/image.h>

namespace aq::reference {

struct TremorParams {
  double amplitude = 2.0;  // pixels
  double wavelength = 24.0;
  double speed = 1.0;
};

ImageF tremor(const ImageF& image, const ImageF* control, double time,
              const TremorParams& params = {});

}  // namespace aq::reference
