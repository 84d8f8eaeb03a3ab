// CPU reference of the `clouds` node: see clouds.h.
#include "aquarelle/reference/clouds.h"

#include "aquarelle/reference/noise_reference.h"

#include <glm/glm.hpp>

#include <algorithm>
#include <cmath>
#include <utility>

namespace aq::reference {
namespace {

glm::dvec3 vec(const float* v) {
  return glm::dvec3(v[0], v[1], v[2]);
}

double density_at(const glm::dvec3& p, double time, const CloudsParams& c) {
  double falloff = 1.0;
  if (c.falloff == 1) falloff = std::clamp((p.y - c.falloff_start) / c.falloff_length, 0.0, 1.0);
  if (c.falloff == 2) {
    const glm::dvec3 centre(c.centre[0], c.centre[1], c.centre[2]);
    double distance = glm::length(p - centre);
    if (c.warp > 0.0) {
      const glm::dvec3 q =
          p * (0.5 * c.scale) + time * glm::dvec3(0.31, -0.47, 0.23) + glm::dvec3(5.2, 1.3, 7.7);
      distance += c.warp * noise::fbm3({q.x, q.y, q.z}, 2);
    }
    falloff = std::clamp(1.0 - distance / c.falloff_length, 0.0, 1.0);
  }
  if (falloff <= 0.0) return 0.0;
  double shape = 1.0;
  if (c.noise > 0.0) {
    const glm::dvec3 q = (p - time * glm::dvec3(c.drift[0], c.drift[1], c.drift[2])) * c.scale;
    const double n = 0.5 + 0.5 * noise::fbm3({q.x, q.y, q.z}, c.octaves);
    shape = 1.0 + (n - 1.0) * c.noise;
  }
  if (shape < c.threshold) return 0.0;
  return c.density * shape * falloff;
}

// The part [t0, t1] of the ray o + t d (0 <= t <= t_end) where the falloff may be non-zero:
// above the height ramp's start, or inside the distance falloff's sphere widened by the warp.
std::pair<double, double> live_segment(const glm::dvec3& o, const glm::dvec3& d, double t_end,
                                       const CloudsParams& c) {
  double t0 = 0.0, t1 = t_end;
  if (c.falloff == 1) {
    if (std::abs(d.y) < 1e-12) {
      if (o.y <= c.falloff_start) t1 = -1.0;
    } else {
      const double t = (c.falloff_start - o.y) / d.y;
      if (d.y > 0.0)
        t0 = std::max(t0, t);
      else
        t1 = std::min(t1, t);
    }
  } else if (c.falloff == 2) {
    const double radius = c.falloff_length + std::max(c.warp, 0.0) * 1.05;
    const glm::dvec3 oc = o - glm::dvec3(c.centre[0], c.centre[1], c.centre[2]);
    const double b = glm::dot(oc, d);
    const double disc = b * b - (glm::dot(oc, oc) - radius * radius);
    if (!(disc > 0.0)) return {0.0, -1.0};
    t0 = std::max(t0, -b - std::sqrt(disc));
    t1 = std::min(t1, -b + std::sqrt(disc));
  }
  return {t0, t1};
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
      const auto [t0, t1] = live_segment(eye, dir, t_end, c);
      if (!(t1 > t0)) continue;
      const double step = (t1 - t0) / c.steps;
      double tau = 0.0;
      for (int k = 0; k < c.steps; ++k)
        tau += density_at(eye + (t0 + (k + 0.5) * step) * dir, time, c);
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
