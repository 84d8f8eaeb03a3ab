// CPU reference of the `tint` node: see tint.h.
#include "aquarelle/reference/tint.h"

#include <algorithm>

namespace aq::reference {

ImageF tint(const ImageF& image, const TintParams& params) {
  ImageF out = image;
  for (int y = 0; y < image.height; ++y)
    for (int x = 0; x < image.width; ++x)
      for (int c = 0; c < std::min(image.channels, 3); ++c) {
        const double v = image.at(x, y, c);
        out.at(x, y, c) = static_cast<float>(v + (params.tint[c] - v) * params.amount);
      }
  return out;
}

}  // namespace aq::reference
