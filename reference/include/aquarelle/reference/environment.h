// CPU reference of the `environment` node in double precision (plugins/environment/README.md):
// every background pixel (id 0) shows the equirectangular panorama along its view ray,
// bilinear, wrapping in longitude and clamped at the poles, times `intensity`; object pixels
// keep the picture.
#pragma once

#include <aquarelle/core/image.h>

#include <array>

namespace aq::reference {

struct EnvironmentParams {
  std::array<double, 3> eye{0.0, 0.0, 0.0};
  std::array<double, 3> target{0.0, 0.0, -1.0};
  double fov_degrees = 60.0;  // vertical, clamped to [1, 179] as the camera does
  double rotation_degrees = 0.0;
  double intensity = 1.0;
};

// `image` (the picture of the objects) and `id` (channel 0, same size) give the output's size;
// alpha 1 on the background, the input's elsewhere.
ImageF environment(const ImageF& image, const ImageF& id, const ImageF& panorama,
                   const EnvironmentParams& params);

// Cube map mode: faces in the order +x, -x, +y, -y, +z, -z (the README's table of right and up
// directions); a null face shows `missing` (linear rgb).
ImageF environment_cube(const ImageF& image, const ImageF& id, const ImageF* const faces[6],
                        const std::array<double, 3>& missing, const EnvironmentParams& params);

}  // namespace aq::reference
