// The `environment` node's maths (plugins/environment/README.md), in double precision.
#include "aquarelle/reference/environment.h"

#include <algorithm>
#include <cmath>

namespace aq::reference {

namespace {

using Vec = std::array<double, 3>;

Vec normalized(const Vec& v) {
  const double length = std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
  return {v[0] / length, v[1] / length, v[2] / length};
}

Vec cross(const Vec& a, const Vec& b) {
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}

// The panorama's bilinear texel at (u, v) in [0, 1]: columns wrap, rows clamp.
Vec lookup(const ImageF& pano, double u, double v) {
  const double ax = u * pano.width - 0.5, ay = v * pano.height - 0.5;
  const int i0 = static_cast<int>(std::floor(ax)), j0 = static_cast<int>(std::floor(ay));
  const double fx = ax - i0, fy = ay - j0;
  auto texel = [&](int i, int j, int c) {
    i = ((i % pano.width) + pano.width) % pano.width;
    j = std::clamp(j, 0, pano.height - 1);
    return static_cast<double>(pano.at(i, j, std::min(c, pano.channels - 1)));
  };
  Vec out{};
  for (int c = 0; c < 3; ++c) {
    const double bottom = texel(i0, j0, c) + fx * (texel(i0 + 1, j0, c) - texel(i0, j0, c));
    const double top =
        texel(i0, j0 + 1, c) + fx * (texel(i0 + 1, j0 + 1, c) - texel(i0, j0 + 1, c));
    out[c] = bottom + fy * (top - bottom);
  }
  return out;
}

}  // namespace

ImageF environment(const ImageF& image, const ImageF& id, const ImageF& panorama,
                   const EnvironmentParams& p) {
  ImageF out = image;
  const Vec forward =
      normalized({p.target[0] - p.eye[0], p.target[1] - p.eye[1], p.target[2] - p.eye[2]});
  const Vec right = normalized(cross(forward, {0.0, 1.0, 0.0}));
  const Vec up = cross(right, forward);
  const double pi = 3.14159265358979323846;
  const double tan_half = std::tan(std::clamp(p.fov_degrees, 1.0, 179.0) * pi / 360.0);
  const double aspect = double(image.width) / double(image.height);
  for (int y = 0; y < image.height; ++y) {
    for (int x = 0; x < image.width; ++x) {
      if (std::round(id.at(x, y, 0)) != 0.0) continue;
      const double nx = 2.0 * (x + 0.5) / image.width - 1.0;
      const double ny = 2.0 * (y + 0.5) / image.height - 1.0;
      Vec d;
      for (int k = 0; k < 3; ++k)
        d[k] = forward[k] + nx * tan_half * aspect * right[k] + ny * tan_half * up[k];
      d = normalized(d);
      const double longitude = std::atan2(d[0], -d[2]) + p.rotation_degrees * pi / 180.0;
      double u = 0.5 + longitude / (2.0 * pi);
      u -= std::floor(u);
      const double v = 0.5 + std::asin(std::clamp(d[1], -1.0, 1.0)) / pi;
      const Vec colour = lookup(panorama, u, v);
      for (int c = 0; c < 3 && c < out.channels; ++c)
        out.at(x, y, c) = static_cast<float>(p.intensity * colour[c]);
      if (out.channels > 3) out.at(x, y, 3) = 1.0f;
    }
  }
  return out;
}

}  // namespace aq::reference
