// CPU reference of the `pigment` node (plugins/pigment/README.md) in double precision:
// Bousseau's density modification C' = C(1 − (1 − C)(d − 1)), d = clamp(1 + weight·n, 0, 2),
// for turbulence, grain and paper in turn, with the textures on the dynamic canvas (screen) or
// at the world position (object). Procedural textures come from noise_reference.h.
#pragma once

#include <aquarelle/core/image.h>

#include <array>

namespace aq::reference {

struct PigmentParams {
  bool object_anchoring = false;
  std::array<double, 3> weights{1.6, 1.0, 1.6};          // turbulence, grain, paper
  std::array<double, 3> frequencies{3.0, 360.0, 100.0};  // cells per image height / world unit
  double world_scale = 1.0;
  int seed = 0;
  // Dynamic canvas from the camera (0 without one).
  double pan_x = 0.0;
  double pan_y = 0.0;
  double zoom = 0.0;
};

// Bousseau et al. 2006: one density applied to one channel value.
double apply_density(double c, double d);

// `textures` entries may be null (procedural); `position` may be null (screen anchoring).
ImageF pigment(const ImageF& image, const std::array<const ImageF*, 3>& textures,
               const ImageF* position, const PigmentParams& params);

}  // namespace aq::reference
