// CPU reference of the shared procedural noise: see noise_reference.h.
#include "aquarelle/reference/noise_reference.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <numbers>

namespace aq::reference::noise {
namespace {

constexpr uint32_t kLcgMultiplier = 1664525u;
constexpr uint32_t kLcgIncrement = 1013904223u;

// Perlin's quintic fade and its derivative.
double fade(double t) {
  return t * t * t * (t * (t * 6.0 - 15.0) + 10.0);
}
double fade_derivative(double t) {
  return 30.0 * t * t * (t - 1.0) * (t - 1.0);
}

uint32_t cell_bits(int64_t cell) {
  return static_cast<uint32_t>(static_cast<int32_t>(cell));
}

Vec2 perlin2_gradient(int64_t cx, int64_t cy, uint32_t seed) {
  const uint32_t index = pcg3d(cell_bits(cx), cell_bits(cy), seed)[0] & 7u;
  const double angle = index * std::numbers::pi / 4.0;  // 8 directions, 45 degrees apart
  return {std::cos(angle), std::sin(angle)};
}

Vec3 perlin3_gradient(int64_t cx, int64_t cy, int64_t cz) {
  // Perlin's 12 cube edge midpoints, 4 of them repeated to make 16.
  static constexpr int kEdges[16][3] = {{1, 1, 0}, {-1, 1, 0}, {1, -1, 0}, {-1, -1, 0},
                                        {1, 0, 1}, {-1, 0, 1}, {1, 0, -1}, {-1, 0, -1},
                                        {0, 1, 1}, {0, -1, 1}, {0, 1, -1}, {0, -1, -1},
                                        {1, 1, 0}, {-1, 1, 0}, {0, -1, 1}, {0, -1, -1}};
  const uint32_t index = pcg3d(cell_bits(cx), cell_bits(cy), cell_bits(cz))[0] & 15u;
  return {double(kEdges[index][0]), double(kEdges[index][1]), double(kEdges[index][2])};
}

}  // namespace

std::array<uint32_t, 2> pcg2d(uint32_t x, uint32_t y) {
  x = x * kLcgMultiplier + kLcgIncrement;
  y = y * kLcgMultiplier + kLcgIncrement;
  x += y * kLcgMultiplier;
  y += x * kLcgMultiplier;
  x ^= x >> 16u;
  y ^= y >> 16u;
  x += y * kLcgMultiplier;
  y += x * kLcgMultiplier;
  x ^= x >> 16u;
  y ^= y >> 16u;
  return {x, y};
}

std::array<uint32_t, 3> pcg3d(uint32_t x, uint32_t y, uint32_t z) {
  x = x * kLcgMultiplier + kLcgIncrement;
  y = y * kLcgMultiplier + kLcgIncrement;
  z = z * kLcgMultiplier + kLcgIncrement;
  x += y * z;
  y += z * x;
  z += x * y;
  x ^= x >> 16u;
  y ^= y >> 16u;
  z ^= z >> 16u;
  x += y * z;
  y += z * x;
  z += x * y;
  return {x, y, z};
}

double unit_from_hash(uint32_t h) {
  return double(h >> 8u) / 16777216.0;
}

int64_t wrap_cell(int64_t cell, double period) {
  const int64_t n = std::llround(period);
  if (n <= 0) return cell;
  const int64_t m = cell % n;
  return m < 0 ? m + n : m;
}

double hash12(Vec2 p) {
  const auto h = pcg2d(cell_bits(int64_t(std::floor(p.x))), cell_bits(int64_t(std::floor(p.y))));
  return unit_from_hash(h[0]);
}

double perlin2(Vec2 p, Vec2 period, uint32_t seed) {
  const double fx = std::floor(p.x), fy = std::floor(p.y);
  const int64_t ix = int64_t(fx), iy = int64_t(fy);
  const double rx = p.x - fx, ry = p.y - fy;
  double sum = 0.0;
  // Sum over the cell's corners of the corner's linear ramp weighted by the fade of the
  // distance along each axis.
  for (int cy = 0; cy <= 1; ++cy) {
    for (int cx = 0; cx <= 1; ++cx) {
      const Vec2 g =
          perlin2_gradient(wrap_cell(ix + cx, period.x), wrap_cell(iy + cy, period.y), seed);
      const double ramp = g.x * (rx - cx) + g.y * (ry - cy);
      const double wx = cx ? fade(rx) : 1.0 - fade(rx);
      const double wy = cy ? fade(ry) : 1.0 - fade(ry);
      sum += wx * wy * ramp;
    }
  }
  return std::numbers::sqrt2 * sum;
}

ValueAndGradient perlin3_with_gradient(Vec3 p, Vec3 period) {
  const double fx = std::floor(p.x), fy = std::floor(p.y), fz = std::floor(p.z);
  const int64_t ix = int64_t(fx), iy = int64_t(fy), iz = int64_t(fz);
  const double r[3] = {p.x - fx, p.y - fy, p.z - fz};
  ValueAndGradient out;
  for (int c = 0; c < 8; ++c) {
    const int corner[3] = {c & 1, (c >> 1) & 1, (c >> 2) & 1};
    const Vec3 g =
        perlin3_gradient(wrap_cell(ix + corner[0], period.x), wrap_cell(iy + corner[1], period.y),
                         wrap_cell(iz + corner[2], period.z));
    const double d[3] = {r[0] - corner[0], r[1] - corner[1], r[2] - corner[2]};
    const double ramp = g.x * d[0] + g.y * d[1] + g.z * d[2];
    double w[3], dw[3];
    for (int a = 0; a < 3; ++a) {
      w[a] = corner[a] ? fade(r[a]) : 1.0 - fade(r[a]);
      dw[a] = corner[a] ? fade_derivative(r[a]) : -fade_derivative(r[a]);
    }
    const double weight = w[0] * w[1] * w[2];
    out.value += weight * ramp;
    // Product rule: derivative of the weight times the ramp plus the weight times the ramp's
    // (constant) gradient.
    out.gradient.x += dw[0] * w[1] * w[2] * ramp + weight * g.x;
    out.gradient.y += w[0] * dw[1] * w[2] * ramp + weight * g.y;
    out.gradient.z += w[0] * w[1] * dw[2] * ramp + weight * g.z;
  }
  return out;
}

double perlin3(Vec3 p, Vec3 period) {
  return perlin3_with_gradient(p, period).value;
}

double fbm2(Vec2 p, Vec2 period, int octaves, uint32_t seed) {
  double sum = 0.0, total = 0.0;
  for (int k = 0; k < std::max(octaves, 1); ++k) {
    const double frequency = std::ldexp(1.0, k);
    const double amplitude = std::ldexp(1.0, -k);
    sum += amplitude * perlin2({p.x * frequency, p.y * frequency},
                               {period.x * frequency, period.y * frequency},
                               seed + uint32_t(k) * 0x9E3779B9u);
    total += amplitude;
  }
  return sum / total;
}

double gaussian_noise(Vec2 cell, float seed) {
  const auto h = pcg3d(cell_bits(int64_t(std::floor(cell.x))),
                       cell_bits(int64_t(std::floor(cell.y))), std::bit_cast<uint32_t>(seed));
  const double u1 = (double(h[0] >> 8u) + 1.0) / 16777216.0;  // (0,1]: log stays finite
  const double u2 = unit_from_hash(h[1]);
  return std::sqrt(-2.0 * std::log(u1)) * std::cos(2.0 * std::numbers::pi * u2);
}

double worley2(Vec2 p, Vec2 period, uint32_t seed) {
  const double fx = std::floor(p.x), fy = std::floor(p.y);
  const int64_t ix = int64_t(fx), iy = int64_t(fy);
  double nearest = 1e300;
  // A wide 7x7 search (wider than the shader's, which is exact as well) so the reference does
  // not depend on the shader's argument about which cells can hold the nearest point.
  for (int oy = -3; oy <= 3; ++oy) {
    for (int ox = -3; ox <= 3; ++ox) {
      const auto h = pcg3d(cell_bits(wrap_cell(ix + ox, period.x)),
                           cell_bits(wrap_cell(iy + oy, period.y)), seed);
      const double px = fx + ox + unit_from_hash(h[0]);
      const double py = fy + oy + unit_from_hash(h[1]);
      nearest = std::min(nearest, std::hypot(px - p.x, py - p.y));
    }
  }
  return nearest;
}

double fbm3(Vec3 p, int octaves) {
  double sum = 0.0, amplitude = 1.0, total = 0.0, frequency = 1.0;
  for (int k = 0; k < std::max(octaves, 1); ++k) {
    const Vec3 q{p.x * frequency + k * 17.13, p.y * frequency + k * 31.71,
                 p.z * frequency + k * 47.37};
    sum += amplitude * perlin3(q, Vec3{0.0, 0.0, 0.0});
    total += amplitude;
    amplitude *= 0.5;
    frequency *= 2.0;
  }
  return sum / total;
}

double perlin3_bent(Vec3 p, double bend) {
  const double fx = std::floor(p.x), fy = std::floor(p.y), fz = std::floor(p.z);
  const int64_t ix = int64_t(fx), iy = int64_t(fy), iz = int64_t(fz);
  const double r[3] = {p.x - fx, p.y - fy, p.z - fz};
  const double e0 = 0.5 * bend, e1 = 1.0 - 0.5 * bend;
  double u[3];
  for (int a = 0; a < 3; ++a) {
    const double t = std::clamp((r[a] - e0) / (e1 - e0), 0.0, 1.0);
    u[a] = t * t * (3.0 - 2.0 * t);  // GLSL's smoothstep
  }
  double value = 0.0;
  for (int c = 0; c < 8; ++c) {
    const int corner[3] = {c & 1, (c >> 1) & 1, (c >> 2) & 1};
    const Vec3 g = perlin3_gradient(wrap_cell(ix + corner[0], 0.0), wrap_cell(iy + corner[1], 0.0),
                                    wrap_cell(iz + corner[2], 0.0));
    const double ramp =
        g.x * (r[0] - corner[0]) + g.y * (r[1] - corner[1]) + g.z * (r[2] - corner[2]);
    double weight = 1.0;
    for (int a = 0; a < 3; ++a) weight *= corner[a] ? u[a] : 1.0 - u[a];
    value += weight * ramp;
  }
  return value;
}

double fbm3_bent(Vec3 p, int octaves, double bend) {
  double sum = 0.0, amplitude = 1.0, total = 0.0, frequency = 1.0;
  for (int k = 0; k < std::max(octaves, 1); ++k) {
    const Vec3 q{p.x * frequency + k * 17.13, p.y * frequency + k * 31.71,
                 p.z * frequency + k * 47.37};
    sum += amplitude * perlin3_bent(q, bend);
    total += amplitude;
    amplitude *= 0.5;
    frequency *= 2.0;
  }
  return sum / total;
}

}  // namespace aq::reference::noise
