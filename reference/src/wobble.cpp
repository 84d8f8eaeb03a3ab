// CPU reference of paper wobble and of the wobble node's procedural paper (Worley + fBm).
#include "aquarelle/reference/wobble.h"

#include "aquarelle/reference/bilinear.h"
#include "aquarelle/reference/noise_reference.h"

#include <algorithm>
#include <cmath>

namespace aq::reference {

ImageF wobble(const ImageF& image, const ImageF& paper, double strength) {
  ImageF out(image.width, image.height, 4);
  const double step_u = 1.0 / paper.width;
  const double step_v = 1.0 / paper.height;
  for (int y = 0; y < image.height; ++y) {
    for (int x = 0; x < image.width; ++x) {
      const double u = (x + 0.5) / image.width;
      const double v = (y + 0.5) / image.height;
      // Height slope per paper pixel: difference over two paper pixels, divided by two.
      const double slope_x =
          (sample_bilinear(paper, u + step_u, v, 0) - sample_bilinear(paper, u - step_u, v, 0)) /
          2.0;
      const double slope_y =
          (sample_bilinear(paper, u, v + step_v, 0) - sample_bilinear(paper, u, v - step_v, 0)) /
          2.0;
      const double lookup_u = u + strength * slope_x * step_u;
      const double lookup_v = v + strength * slope_y * step_v;
      for (int c = 0; c < 4; ++c) {
        out.at(x, y, c) = static_cast<float>(sample_bilinear(image, lookup_u, lookup_v, c));
      }
    }
  }
  return out;
}

ImageF procedural_paper(int columns, int lines, double grain, int seed) {
  ImageF paper(columns, lines, 4, 1.0f);
  const double offset_x = std::fmod(seed * 113.0, 4096.0);
  const double offset_y = std::fmod(seed * 71.0, 4096.0);
  for (int j = 0; j < lines; ++j) {
    for (int i = 0; i < columns; ++i) {
      const noise::Vec2 q{(i + 0.5) / grain + offset_x, (j + 0.5) / grain + offset_y};
      const double cells = 1.0 - std::min(noise::worley2(q, {0.0, 0.0}), 1.0);
      const double fibres = 0.5 + 0.5 * noise::fbm2({q.x * 0.37, q.y * 0.37}, {0.0, 0.0}, 4);
      const double height = std::clamp(0.6 * cells + 0.4 * fibres, 0.0, 1.0);
      for (int c = 0; c < 3; ++c) paper.at(i, j, c) = static_cast<float>(height);
    }
  }
  return paper;
}

int procedural_paper_columns(int image_width, int image_height, int lines) {
  const double aspect = static_cast<double>(image_width) / image_height;
  return std::max(1, static_cast<int>(std::lround(lines * aspect)));
}

}  // namespace aq::reference
