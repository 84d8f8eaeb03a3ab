// CPU reference of the `clouds` node: see clouds.h.
#include "aquarelle/reference/clouds.h"

#include "aquarelle/reference/noise_reference.h"

#include <glm/glm.hpp>

#include <algorithm>
#include <cmath>

namespace aq::reference {
namespace {

glm::dvec3 vec(const float* v) {
  return glm::dvec3(v[0], v[1], v[2]);
}

double density_at(const glm::dvec3& p, double time, const CloudsParams& c) {
  double shape = 1.0;
  if (c.noise > 0.0) {
    const glm::dvec3 q = (p - time * glm::dvec3(c.drift[0], c.drift[1], c.drift[2])) * c.scale;
    const double n = 0.5 + 0.5 * noise::fbm3({q.x, q.y, q.z}, c.octaves);
    shape = 1.0 + (n - 1.0) * c.noise;
  }
  if (shape < c.threshold) return 0.0;
  double falloff = 1.0;
  if (c.falloff == 1) falloff = std::clamp((p.y - c.falloff_start) / c.falloff_length, 0.0, 1.0);
  if (c.falloff == 2) {
    const glm::dvec3 centre(c.centre[0], c.centre[1], c.centre[2]);
    falloff = std::clamp(1.0 - glm::length(p - centre) / c.falloff_length, 0.0, 1.0);
  }
  return c.density * shape * falloff;
}

}  // namespace

ImageF clouds(const ImageF& image, const aq_camera& camera, const ImageF* depth, double time,
              const CloudsParams& c) {
  if (!(c.density > 0.0) || !(c.max_distance > 0.0)) return image;
  const glm::dvec3 eye = vec(camera.position);
  const glm::dvec3 forward = glm::normalize(vec(camera.target) - eye);
  const glm::dvec3 right = glm::normalize(glm::cross(forward, vec(camera.up)));
  const glm::dvec3 up = glm::cross(right, forward);
  const double tan_half = std::tan(camera.fov_y_degrees * 3.14159265358979323846 / 360.0);
  const double aspect = double(image.width) / image.height;
  ImageF out = image;
  for (int y = 0; y < image.height; ++y)
    for (int x = 0; x < image.width; ++x) {
      const double nx = (x + 0.5) / image.width * 2.0 - 1.0;
      const double ny = (y + 0.5) / image.height * 2.0 - 1.0;
      const glm::dvec3 dir =
          glm::normalize(forward + nx * tan_half * aspect * right + ny * tan_half * up);
      double t_end = c.max_distance;
      if (depth != nullptr) {
        const double d =
            depth->at(std::min(x * depth->width / image.width, depth->width - 1),
                      std::min(y * depth->height / image.height, depth->height - 1), 0);
        const double along = d / std::max(glm::dot(dir, forward), 1e-6);
        if (along >= 0.0) t_end = std::min(t_end, along);
      }
      const double step = t_end / c.steps;
      double tau = 0.0;
      for (int k = 0; k < c.steps; ++k) tau += density_at(eye + (k + 0.5) * step * dir, time, c);
      tau *= step;
      if (!(tau > 0.0)) continue;
      const double t = std::exp(-tau);
      for (int ch = 0; ch < 3; ++ch) {
        out.at(x, y, ch) =
            static_cast<float>(image.at(x, y, ch) * t + c.light_color[ch] * (1.0 - t));
      }
    }
  return out;
}

}  // namespace aq::reference
