// CPU reference of the `clouds` node in double precision (plugins/clouds/README.md): per pixel,
// the camera ray through the pixel centre (pinhole from the camera's position, target, up and
// vertical field of view), stopped at the depth image's surface or max_distance, midpoint
// steps of ρ = density · shape · falloff over the part of the ray where the falloff can be
// non-zero, out = C e^(−τ) + light (1 − e^(−τ)). One ray per pixel: the node at resolution 1.
#pragma once

#include <aquarelle/core/image.h>
#include <aquarelle/plugin.h>

#include <array>

namespace aq::reference {

struct CloudsParams {
  double density = 0.3;
  double noise = 1.0;
  double scale = 0.3;
  int octaves = 4;
  double threshold = 0.0;
  int falloff = 1;  // 0 none, 1 height, 2 distance
  double falloff_start = 2.0;
  double falloff_length = 4.0;
  std::array<double, 3> centre{0, 0, 0};
  std::array<double, 3> drift{0.4, 0.0, 0.15};
  std::array<double, 3> light_color{1.0, 0.92, 0.8};
  int steps = 32;
  double max_distance = 40.0;
  double warp = 0.0;  // world units of animated FBM added to the distance falloff's distance
};

ImageF clouds(const ImageF& image, const aq_camera& camera, const ImageF* depth, double time,
              const CloudsParams& params = {});

}  // namespace aq::reference
