// GL_LINEAR + GL_CLAMP_TO_EDGE lookup in double precision (OpenGL 4.5 core §8.14.2).
#include "aquarelle/reference/bilinear.h"

#include <algorithm>
#include <cmath>

namespace aq::reference {

double sample_bilinear(const ImageF& image, double u, double v, int channel) {
  const double x = u * image.width - 0.5;
  const double y = v * image.height - 0.5;
  const double x0 = std::floor(x);
  const double y0 = std::floor(y);
  const double fx = x - x0;
  const double fy = y - y0;
  auto texel = [&](double i, double j) {
    // Clamp in double first so that far-away (or non-finite) coordinates stay well defined.
    const int ci = static_cast<int>(std::clamp(i, 0.0, image.width - 1.0));
    const int cj = static_cast<int>(std::clamp(j, 0.0, image.height - 1.0));
    return static_cast<double>(image.at(ci, cj, channel));
  };
  const double bottom = (1.0 - fx) * texel(x0, y0) + fx * texel(x0 + 1, y0);
  const double top = (1.0 - fx) * texel(x0, y0 + 1) + fx * texel(x0 + 1, y0 + 1);
  return (1.0 - fy) * bottom + fy * top;
}

}  // namespace aq::reference
