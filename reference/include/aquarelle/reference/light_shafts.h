// CPU reference of the `light_shafts` node in double precision (plugins/light_shafts/README.md):
// along each view ray, the caustics' excess over flat water where the light through each point
// left the water plane, weighted by the exact integral of sigma exp(-sigma t) over each of
// `steps` segments, times strength and the light's colour, added to the picture.
#pragma once

#include <aquarelle/core/image.h>

#include <array>

namespace aq::reference {

struct LightShaftsParams {
  std::array<double, 3> eye{0.0, 0.0, 0.0};
  std::array<double, 3> target{0.0, 0.0, -1.0};
  double fov_degrees = 50.0;
  std::array<double, 3> light_direction{0.0, -1.0, 0.0};  // unit
  std::array<double, 3> light_color{1.0, 1.0, 1.0};
  double water_height = 6.0;
  double tile = 4.0;
  double strength = 1.0;
  double extinction = 0.1;
  int steps = 24;
  double max_distance = 40.0;
};

// `position`: world xyz, alpha 1 where a surface is (same size as `image`); `caustics`: one
// period of the pattern, read bilinearly with wrap-around.
ImageF light_shafts(const ImageF& image, const ImageF& position, const ImageF& caustics,
                    const LightShaftsParams& params);

}  // namespace aq::reference
