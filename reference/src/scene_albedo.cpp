#include "aquarelle/reference/scene_albedo.h"

#include <cmath>

namespace aq::reference {

double srgb_to_linear(double encoded) {
  return encoded <= 0.04045 ? encoded / 12.92 : std::pow((encoded + 0.055) / 1.055, 2.4);
}

glm::dvec4 sample_bilinear_repeat(const RefTexture& texture, const glm::dvec2& uv) {
  const double x = uv.x * texture.width - 0.5, y = uv.y * texture.height - 0.5;
  const double fx = std::floor(x), fy = std::floor(y);
  const double ax = x - fx, ay = y - fy;
  auto wrap = [](long i, int n) { return static_cast<int>(((i % n) + n) % n); };
  const long x0 = static_cast<long>(fx), y0 = static_cast<long>(fy);
  const glm::dvec4 a = texture.at(wrap(x0, texture.width), wrap(y0, texture.height));
  const glm::dvec4 b = texture.at(wrap(x0 + 1, texture.width), wrap(y0, texture.height));
  const glm::dvec4 c = texture.at(wrap(x0, texture.width), wrap(y0 + 1, texture.height));
  const glm::dvec4 d = texture.at(wrap(x0 + 1, texture.width), wrap(y0 + 1, texture.height));
  return (1 - ay) * ((1 - ax) * a + ax * b) + ay * ((1 - ax) * c + ax * d);
}

std::optional<RefHit> reference_albedo(const std::vector<RefTriangle>& triangles,
                                       const RefCamera& camera, int width, int height, int x, int y,
                                       double dx, double dy) {
  // Camera basis as gluLookAt builds it (world up +y) and the ray through the pixel.
  const glm::dvec3 forward = glm::normalize(camera.target - camera.eye);
  const glm::dvec3 right = glm::normalize(glm::cross(forward, glm::dvec3(0, 1, 0)));
  const glm::dvec3 up = glm::cross(right, forward);
  const double tan_half = std::tan(camera.fov_y_degrees * 3.14159265358979323846 / 360.0);
  const double aspect = static_cast<double>(width) / height;
  const double ndc_x = 2.0 * (x + 0.5 + dx) / width - 1.0;
  const double ndc_y = 2.0 * (y + 0.5 + dy) / height - 1.0;
  const glm::dvec3 direction =
      glm::normalize(forward + ndc_x * tan_half * aspect * right + ndc_y * tan_half * up);

  std::optional<RefHit> nearest;
  double nearest_t = 1e300;
  for (size_t i = 0; i < triangles.size(); ++i) {
    const RefTriangle& tri = triangles[i];
    // Möller-Trumbore.
    const glm::dvec3 e1 = tri.p[1] - tri.p[0], e2 = tri.p[2] - tri.p[0];
    const glm::dvec3 h = glm::cross(direction, e2);
    const double det = glm::dot(e1, h);
    if (std::abs(det) < 1e-14) continue;
    const glm::dvec3 s = camera.eye - tri.p[0];
    const double u = glm::dot(s, h) / det;
    if (u < 0.0 || u > 1.0) continue;
    const glm::dvec3 q = glm::cross(s, e1);
    const double v = glm::dot(direction, q) / det;
    if (v < 0.0 || u + v > 1.0) continue;
    const double t = glm::dot(e2, q) / det;
    if (t <= 0.0 || t >= nearest_t) continue;
    const double w = 1.0 - u - v;
    const glm::dvec2 uv = w * tri.uv[0] + u * tri.uv[1] + v * tri.uv[2];
    const glm::dvec4 texel =
        tri.texture != nullptr ? sample_bilinear_repeat(*tri.texture, uv) : glm::dvec4(1.0);
    if (texel.a < tri.alpha_cutoff) continue;  // a hole: look further
    const glm::dvec3 color = w * tri.color[0] + u * tri.color[1] + v * tri.color[2];
    nearest = RefHit{color * glm::dvec3(texel), texel.a, i};
    nearest_t = t;
  }
  return nearest;
}

}  // namespace aq::reference
