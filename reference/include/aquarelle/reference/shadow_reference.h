// CPU reference for shadow tests: exact ray casting against an axis-aligned box, the occluder
// of the `plane_box` scene preset. A point is in shadow when the ray from it towards the light
// meets the box.
#pragma once

#include <aquarelle/core/image.h>

#include <array>

namespace aq::reference {

using Vec3d = std::array<double, 3>;

// True when the ray origin + t * direction, t > t_min, meets the box [lo, hi] (slab method).
bool ray_hits_box(const Vec3d& origin, const Vec3d& direction, const Vec3d& lo, const Vec3d& hi,
                  double t_min = 1e-9);

// Per pixel of a gbuffer position image (w = 1 on geometry): 1 lit, 0 in the box's shadow
// for light travelling along `light_direction`; -1 on the background (w = 0).
ImageF box_shadow_mask(const ImageF& position, const Vec3d& light_direction, const Vec3d& lo,
                       const Vec3d& hi);

}  // namespace aq::reference
