// Exact box shadows by ray casting (see shadow_reference.h).
#include "aquarelle/reference/shadow_reference.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace aq::reference {

bool ray_hits_box(const Vec3d& origin, const Vec3d& direction, const Vec3d& lo, const Vec3d& hi,
                  double t_min) {
  double near_t = t_min, far_t = std::numeric_limits<double>::infinity();
  for (int k = 0; k < 3; ++k) {
    if (std::abs(direction[k]) < 1e-300) {
      if (origin[k] < lo[k] || origin[k] > hi[k]) return false;
      continue;
    }
    double t0 = (lo[k] - origin[k]) / direction[k];
    double t1 = (hi[k] - origin[k]) / direction[k];
    if (t0 > t1) std::swap(t0, t1);
    near_t = std::max(near_t, t0);
    far_t = std::min(far_t, t1);
    if (near_t > far_t) return false;
  }
  return true;
}

ImageF box_shadow_mask(const ImageF& position, const Vec3d& light_direction, const Vec3d& lo,
                       const Vec3d& hi) {
  ImageF mask(position.width, position.height, 1, 0.0f);
  const Vec3d towards_light{-light_direction[0], -light_direction[1], -light_direction[2]};
  for (int y = 0; y < position.height; ++y) {
    for (int x = 0; x < position.width; ++x) {
      if (position.at(x, y, 3) < 0.5f) {
        mask.at(x, y, 0) = -1.0f;
        continue;
      }
      Vec3d p{position.at(x, y, 0), position.at(x, y, 1), position.at(x, y, 2)};
      mask.at(x, y, 0) = ray_hits_box(p, towards_light, lo, hi) ? 0.0f : 1.0f;
    }
  }
  return mask;
}

}  // namespace aq::reference
