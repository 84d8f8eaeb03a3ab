// The `environment` node's maths (plugins/environment/README.md), in double precision.
#include "aquarelle/reference/environment.h"

#include <algorithm>
#include <cmath>

#include "vector3.h"

namespace aq::reference {

namespace {

using vector3::cross;
using vector3::normalized;
using vector3::Vec;

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

// The view ray of pixel (x, y) of a width x height picture (README).
struct ViewRays {
  Vec forward, right, up;
  double tan_half, aspect;
  ViewRays(const EnvironmentParams& p, int width, int height) {
    forward = normalized({p.target[0] - p.eye[0], p.target[1] - p.eye[1], p.target[2] - p.eye[2]});
    right = normalized(cross(forward, {0.0, 1.0, 0.0}));
    up = cross(right, forward);
    tan_half = std::tan(std::clamp(p.fov_degrees, 1.0, 179.0) * 3.14159265358979323846 / 360.0);
    aspect = double(width) / double(height);
  }
  Vec at(int x, int y, int width, int height) const {
    const double nx = 2.0 * (x + 0.5) / width - 1.0, ny = 2.0 * (y + 0.5) / height - 1.0;
    Vec d;
    for (int k = 0; k < 3; ++k)
      d[k] = forward[k] + nx * tan_half * aspect * right[k] + ny * tan_half * up[k];
    return normalized(d);
  }
};

// Face f's bilinear texel at (u, v) in [0, 1], texels clamped to the face.
Vec face_lookup(const ImageF& face, double u, double v) {
  const double ax = u * face.width - 0.5, ay = v * face.height - 0.5;
  const int i0 = static_cast<int>(std::floor(ax)), j0 = static_cast<int>(std::floor(ay));
  const double fx = ax - i0, fy = ay - j0;
  auto texel = [&](int i, int j, int c) {
    return static_cast<double>(
        face.at(std::clamp(i, 0, face.width - 1), std::clamp(j, 0, face.height - 1), c));
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

ImageF environment_cube(const ImageF& image, const ImageF& id, const ImageF* const faces[6],
                        const std::array<double, 3>& missing, const EnvironmentParams& p) {
  // Right and up of each face (README table): +x, -x, +y, -y, +z, -z.
  static const Vec kRight[6] = {{0, 0, 1}, {0, 0, -1}, {1, 0, 0}, {1, 0, 0}, {-1, 0, 0}, {1, 0, 0}};
  static const Vec kUp[6] = {{0, 1, 0}, {0, 1, 0}, {0, 0, 1}, {0, 0, -1}, {0, 1, 0}, {0, 1, 0}};
  ImageF out = image;
  const ViewRays rays(p, image.width, image.height);
  for (int y = 0; y < image.height; ++y) {
    for (int x = 0; x < image.width; ++x) {
      if (std::round(id.at(x, y, 0)) != 0.0) continue;
      const Vec d = rays.at(x, y, image.width, image.height);
      // The largest |component|; ties: x before y before z.
      int axis = 0;
      if (std::abs(d[1]) > std::abs(d[axis])) axis = 1;
      if (std::abs(d[2]) > std::abs(d[axis])) axis = 2;
      const int f = 2 * axis + (d[axis] < 0.0 ? 1 : 0);
      const double m = std::abs(d[axis]);
      const double a = (d[0] * kRight[f][0] + d[1] * kRight[f][1] + d[2] * kRight[f][2]) / m;
      const double b = (d[0] * kUp[f][0] + d[1] * kUp[f][1] + d[2] * kUp[f][2]) / m;
      const Vec colour =
          faces[f] == nullptr ? missing : face_lookup(*faces[f], 0.5 * (a + 1.0), 0.5 * (b + 1.0));
      for (int c = 0; c < 3 && c < out.channels; ++c)
        out.at(x, y, c) = static_cast<float>(p.intensity * colour[c]);  // missing too
      if (out.channels > 3) out.at(x, y, 3) = 1.0f;
    }
  }
  return out;
}

ImageF environment(const ImageF& image, const ImageF& id, const ImageF& panorama,
                   const EnvironmentParams& p) {
  ImageF out = image;
  const double pi = 3.14159265358979323846;
  const ViewRays rays(p, image.width, image.height);
  for (int y = 0; y < image.height; ++y) {
    for (int x = 0; x < image.width; ++x) {
      if (std::round(id.at(x, y, 0)) != 0.0) continue;
      const Vec d = rays.at(x, y, image.width, image.height);
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
