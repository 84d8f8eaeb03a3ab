// CPU Perlin gradient noise (Perlin 2002, "improved noise") with a permutation shuffled from a
// seed by our own generator, so the sand of a given seed is the same everywhere.
#pragma once

#include "random.h"

#include <array>
#include <cmath>
#include <cstdint>

namespace scene {

class Perlin2 {
 public:
  explicit Perlin2(uint64_t seed) {
    for (int i = 0; i < 256; ++i) perm_[i] = static_cast<uint8_t>(i);
    Random random(seed);
    for (int i = 255; i > 0; --i) {  // Fisher-Yates
      int j = random.integer(0, i);
      std::swap(perm_[i], perm_[j]);
    }
  }

  // Gradient noise in about [-1, 1], zero at integer lattice points.
  double operator()(double x, double y) const {
    double fx = std::floor(x), fy = std::floor(y);
    int ix = static_cast<int>(static_cast<int64_t>(fx) & 255);
    int iy = static_cast<int>(static_cast<int64_t>(fy) & 255);
    double dx = x - fx, dy = y - fy;
    double u = fade(dx), v = fade(dy);
    double n00 = grad(hash(ix, iy), dx, dy);
    double n10 = grad(hash(ix + 1, iy), dx - 1, dy);
    double n01 = grad(hash(ix, iy + 1), dx, dy - 1);
    double n11 = grad(hash(ix + 1, iy + 1), dx - 1, dy - 1);
    double a = n00 + u * (n10 - n00);
    double b = n01 + u * (n11 - n01);
    return a + v * (b - a);
  }

 private:
  static double fade(double t) { return t * t * t * (t * (t * 6 - 15) + 10); }
  int hash(int x, int y) const { return perm_[(perm_[x & 255] + y) & 255]; }
  // Eight unit-ish gradient directions.
  static double grad(int h, double x, double y) {
    switch (h & 7) {
      case 0:
        return x + y;
      case 1:
        return x - y;
      case 2:
        return -x + y;
      case 3:
        return -x - y;
      case 4:
        return x * 1.41421356;
      case 5:
        return -x * 1.41421356;
      case 6:
        return y * 1.41421356;
      default:
        return -y * 1.41421356;
    }
  }
  std::array<uint8_t, 256> perm_{};
};

}  // namespace scene
