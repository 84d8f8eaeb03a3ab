// CPU reference of the screen-space `tremor` node: see tremor.h.
#include "aquarelle/reference/tremor.h"

#include "aquarelle/reference/bilinear.h"
#include "aquarelle/reference/noise_reference.h"

#include <algorithm>
#include <cmath>

namespace aq::reference {

ImageF tremor(const ImageF& image, const ImageF* control, double time, const TremorParams& p) {
  if (!(p.amplitude > 0.0)) return image;
  ImageF out = image;
  const double phase = time * p.speed;
  for (int y = 0; y < image.height; ++y)
    for (int x = 0; x < image.width; ++x) {
      double m = 1.0;
      if (control != nullptr) {
        m = control->at(std::min(x * control->width / image.width, control->width - 1),
                        std::min(y * control->height / image.height, control->height - 1), 3);
        if (!(m > 0.0) || std::isinf(m)) m = 0.0;
      }
      if (m == 0.0) continue;
      const double qx = (x + 0.5) / p.wavelength, qy = (y + 0.5) / p.wavelength;
      const double ox = p.amplitude * m * noise::perlin3({qx, qy, phase}, {0, 0, 0});
      const double oy =
          p.amplitude * m * noise::perlin3({qx + 7.31, qy + 3.17, phase + 11.7}, {0, 0, 0});
      const double u = (x + 0.5 + ox) / image.width, v = (y + 0.5 + oy) / image.height;
      for (int c = 0; c < image.channels; ++c) {
        out.at(x, y, c) = static_cast<float>(sample_bilinear(image, u, v, c));
      }
    }
  return out;
}

}  // namespace aq::reference
