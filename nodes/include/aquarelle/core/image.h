// A CPU image of float pixels, the currency of image I/O, readback and the tests.
#pragma once

#include <cstddef>
#include <vector>

namespace aq {

struct ImageF {
  int width = 0;
  int height = 0;
  int channels = 4;
  std::vector<float> pixels;  // row-major, row 0 at the bottom (GL convention), interleaved

  ImageF() = default;
  ImageF(int w, int h, int c = 4, float fill = 0.0f)
      : width(w), height(h), channels(c), pixels(static_cast<size_t>(w) * h * c, fill) {}

  float& at(int x, int y, int c) {
    return pixels[(static_cast<size_t>(y) * width + x) * channels + c];
  }
  float at(int x, int y, int c) const {
    return pixels[(static_cast<size_t>(y) * width + x) * channels + c];
  }
  bool empty() const { return pixels.empty(); }
};

}  // namespace aq
