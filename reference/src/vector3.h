// Three-vectors in double precision for the references that follow view rays (environment,
// light_shafts).
#pragma once

#include <array>
#include <cmath>

namespace aq::reference::vector3 {

using Vec = std::array<double, 3>;

inline Vec normalized(const Vec& v) {
  const double length = std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
  return {v[0] / length, v[1] / length, v[2] / length};
}

inline Vec cross(const Vec& a, const Vec& b) {
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}

}  // namespace aq::reference::vector3
