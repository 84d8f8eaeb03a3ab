// The `light_shafts` node's maths (plugins/light_shafts/README.md), in double precision.
#include "aquarelle/reference/light_shafts.h"

#include <algorithm>
#include <cmath>

#include "vector3.h"

namespace aq::reference {

namespace {

using vector3::cross;
using vector3::normalized;
using vector3::Vec;

// Periodic bilinear lookup at tile coordinates (u, v), texel centres at (i + 1/2) / size.
Vec caustic(const ImageF& c, double u, double v) {
  const double ax = u * c.width - 0.5, ay = v * c.height - 0.5;
  const double fx0 = std::floor(ax), fy0 = std::floor(ay);
  const double fx = ax - fx0, fy = ay - fy0;
  auto wrap = [](double i, int n) { return static_cast<int>(i - n * std::floor(i / n)); };
  const int i0 = wrap(fx0, c.width), j0 = wrap(fy0, c.height);
  const int i1 = (i0 + 1) % c.width, j1 = (j0 + 1) % c.height;
  Vec out{};
  for (int k = 0; k < 3; ++k) {
    const double bottom = c.at(i0, j0, k) + fx * (c.at(i1, j0, k) - c.at(i0, j0, k));
    const double top = c.at(i0, j1, k) + fx * (c.at(i1, j1, k) - c.at(i0, j1, k));
    out[k] = bottom + fy * (top - bottom);
  }
  return out;
}

// max(c - 1, 0) where the light through q left the water; 0 above the water.
Vec excess(const ImageF& c, const LightShaftsParams& p, const Vec& q) {
  if (q[1] >= p.water_height) return {0.0, 0.0, 0.0};
  const Vec& l = p.light_direction;
  const double up = (p.water_height - q[1]) / -l[1];
  const Vec w = {q[0] - up * l[0], q[1] - up * l[1], q[2] - up * l[2]};
  const Vec value = caustic(c, w[0] / p.tile, w[2] / p.tile);
  return {std::max(value[0] - 1.0, 0.0), std::max(value[1] - 1.0, 0.0),
          std::max(value[2] - 1.0, 0.0)};
}

}  // namespace

ImageF light_shafts(const ImageF& image, const ImageF& position, const ImageF& caustics,
                    const LightShaftsParams& p) {
  ImageF out = image;
  const Vec forward =
      normalized({p.target[0] - p.eye[0], p.target[1] - p.eye[1], p.target[2] - p.eye[2]});
  const Vec right = normalized(cross(forward, {0.0, 1.0, 0.0}));
  const Vec up = cross(right, forward);
  const double tan_half =
      std::tan(std::clamp(p.fov_degrees, 1.0, 179.0) * 3.14159265358979323846 / 360.0);
  const double aspect = double(image.width) / double(image.height);
  for (int y = 0; y < image.height; ++y) {
    for (int x = 0; x < image.width; ++x) {
      Vec ray;
      double distance = p.max_distance;
      if (position.at(x, y, 3) == 1.0f) {
        const Vec to = {position.at(x, y, 0) - p.eye[0], position.at(x, y, 1) - p.eye[1],
                        position.at(x, y, 2) - p.eye[2]};
        const double length = std::sqrt(to[0] * to[0] + to[1] * to[1] + to[2] * to[2]);
        ray = length > 0.0 ? Vec{to[0] / length, to[1] / length, to[2] / length} : forward;
        distance = std::min(length, p.max_distance);
      } else {
        const double nx = 2.0 * (x + 0.5) / image.width - 1.0;
        const double ny = 2.0 * (y + 0.5) / image.height - 1.0;
        Vec d;
        for (int k = 0; k < 3; ++k)
          d[k] = forward[k] + nx * tan_half * aspect * right[k] + ny * tan_half * up[k];
        ray = normalized(d);
      }
      Vec light{0.0, 0.0, 0.0};
      if (p.light_direction[1] < 0.0 && distance > 0.0) {
        const double step = distance / p.steps;
        for (int k = 0; k < p.steps; ++k) {
          const double t = (k + 0.5) * step;
          const Vec q = {p.eye[0] + t * ray[0], p.eye[1] + t * ray[1], p.eye[2] + t * ray[2]};
          const Vec s = excess(caustics, p, q);
          const double weight =
              std::exp(-p.extinction * step * k) - std::exp(-p.extinction * step * (k + 1));
          for (int c = 0; c < 3; ++c) light[c] += s[c] * weight;
        }
      }
      for (int c = 0; c < 3; ++c) {
        out.at(x, y, c) =
            static_cast<float>(image.at(x, y, c) + p.strength * p.light_color[c] * light[c]);
      }
    }
  }
  return out;
}

}  // namespace aq::reference
