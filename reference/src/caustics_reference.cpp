// CPU reference of the `caustics` node: see caustics_reference.h.
#include "aquarelle/reference/caustics_reference.h"

#include "aquarelle/reference/noise_reference.h"

#include <algorithm>
#include <cmath>
#include <vector>

namespace aq::reference {
namespace {

constexpr int kOctaves = 3;
// Offset of octave k along the time axis so the octaves are not aligned at t = 0.
constexpr double kOctaveTimeOffset = 17.0;

int wrap_index(int i, int n) {
  const int m = i % n;
  return m < 0 ? m + n : m;
}

}  // namespace

WaterSample water_surface(double x, double y, const CausticsParams& params) {
  // h = amplitude * sum_k 2^-k N(2^k S x, 2^k S y, 2^k speed t + 17 k) / sum_k 2^-k, with N
  // periodic over 2^k S cells in x and y, so h has period 1 (one tile).
  WaterSample sample;
  double total = 0.0;
  for (int k = 0; k < kOctaves; ++k) {
    const double frequency = params.wave_scale * std::ldexp(1.0, k);
    const double weight = std::ldexp(1.0, -k);
    const auto n = noise::perlin3_with_gradient(
        {frequency * x, frequency * y,
         std::ldexp(1.0, k) * params.speed * params.time + kOctaveTimeOffset * k},
        {frequency, frequency, 0.0});
    sample.height += weight * n.value;
    sample.dhdx += weight * frequency * n.gradient.x;
    sample.dhdy += weight * frequency * n.gradient.y;
    total += weight;
  }
  const double a = params.amplitude / total;
  sample.height *= a;
  sample.dhdx *= a;
  sample.dhdy *= a;
  return sample;
}

Displacement floor_displacement(double x, double y, const CausticsParams& params) {
  const WaterSample w = water_surface(x, y, params);
  // Unit normal of z = h(x, y), pointing up (into the air).
  const double length = std::sqrt(w.dhdx * w.dhdx + w.dhdy * w.dhdy + 1.0);
  const double nx = -w.dhdx / length, ny = -w.dhdy / length, nz = 1.0 / length;
  // Snell's law for the light travelling straight down, I = (0, 0, -1): cos(incidence) = nz,
  // T = eta I + (eta cos_i - cos_t) n with cos_t = sqrt(1 - eta^2 (1 - cos_i^2)).
  if (params.eta >= 1.0) return {};  // no refraction: rays stay vertical
  const double cos_i = nz;
  const double sin_t2 = params.eta * params.eta * (1.0 - cos_i * cos_i);
  if (sin_t2 >= 1.0) return {};  // total internal reflection cannot happen for eta <= 1
  const double cos_t = std::sqrt(1.0 - sin_t2);
  const double k = params.eta * cos_i - cos_t;
  const double tx = k * nx, ty = k * ny, tz = -params.eta + k * nz;
  // Down the refracted ray from the surface (height h) to the floor (height -depth).
  const double drop = std::max(params.depth + w.height, 0.0);
  return {tx * drop / -tz, ty * drop / -tz};
}

ImageF caustics_by_grid(const CausticsParams& params, int grid) {
  const int n = params.resolution;
  const int m = grid;
  // Refracted vertex positions in pixel units; vertex (i, j) with i, j in [0, m].
  std::vector<double> px((m + 1) * (m + 1)), py((m + 1) * (m + 1));
  for (int j = 0; j <= m; ++j) {
    for (int i = 0; i <= m; ++i) {
      // Periodic: the last row and column reuse the first one's displacement.
      const double x = double(i) / m, y = double(j) / m;
      const Displacement d = floor_displacement(double(i % m) / m, double(j % m) / m, params);
      px[j * (m + 1) + i] = (x + d.x) * n;
      py[j * (m + 1) + i] = (y + d.y) * n;
    }
  }
  std::vector<double> sum(size_t(n) * n, 0.0);
  const double original_area = 0.5 * (double(n) / m) * (double(n) / m);  // pixel units

  auto rasterize = [&](double ax, double ay, double bx, double by, double cx, double cy) {
    double area2 = (bx - ax) * (cy - ay) - (by - ay) * (cx - ax);
    const double area = 0.5 * std::abs(area2);
    const double value =
        original_area >= params.max_intensity * area ? params.max_intensity : original_area / area;
    if (area2 < 0.0) {  // make it counter-clockwise (y up) for the edge functions
      std::swap(bx, cx);
      std::swap(by, cy);
      area2 = -area2;
    }
    if (area2 == 0.0) return;  // covers no pixel centre (the GPU draws nothing either)
    const double vx[3] = {ax, bx, cx}, vy[3] = {ay, by, cy};
    const int x0 = int(std::ceil(std::min({ax, bx, cx}) - 0.5));
    const int x1 = int(std::floor(std::max({ax, bx, cx}) - 0.5));
    const int y0 = int(std::ceil(std::min({ay, by, cy}) - 0.5));
    const int y1 = int(std::floor(std::max({ay, by, cy}) - 0.5));
    for (int y = y0; y <= y1; ++y) {
      for (int x = x0; x <= x1; ++x) {
        const double sx = x + 0.5, sy = y + 0.5;
        bool inside = true;
        for (int e = 0; e < 3 && inside; ++e) {
          const double ex = vx[(e + 1) % 3] - vx[e], ey = vy[(e + 1) % 3] - vy[e];
          const double w = ex * (sy - vy[e]) - ey * (sx - vx[e]);
          // Top-left rule: a centre exactly on an edge belongs to one triangle only.
          const bool top_left = (ey < 0.0) || (ey == 0.0 && ex < 0.0);
          inside = w > 0.0 || (w == 0.0 && top_left);
        }
        if (inside) sum[size_t(wrap_index(y, n)) * n + wrap_index(x, n)] += value;
      }
    }
  };

  for (int j = 0; j < m; ++j) {
    for (int i = 0; i < m; ++i) {
      const int v00 = j * (m + 1) + i, v10 = v00 + 1, v01 = v00 + m + 1, v11 = v01 + 1;
      rasterize(px[v00], py[v00], px[v10], py[v10], px[v11], py[v11]);
      rasterize(px[v00], py[v00], px[v11], py[v11], px[v01], py[v01]);
    }
  }
  ImageF out(n, n, 4, 1.0f);
  for (int y = 0; y < n; ++y) {
    for (int x = 0; x < n; ++x) {
      for (int c = 0; c < 3; ++c) out.at(x, y, c) = float(sum[size_t(y) * n + x]);
    }
  }
  return out;
}

ImageF caustics_by_photons(const CausticsParams& params, int samples_per_side) {
  const int n = params.resolution;
  const int s = samples_per_side;
  std::vector<double> sum(size_t(n) * n, 0.0);
  // Each photon carries 1/s^2 of the tile's light; a pixel's intensity is its energy divided
  // by its area 1/n^2.
  const double energy = double(n) * n / (double(s) * s);
  for (int j = 0; j < s; ++j) {
    for (int i = 0; i < s; ++i) {
      const double x = (i + 0.5) / s, y = (j + 0.5) / s;
      const Displacement d = floor_displacement(x, y, params);
      const int px = wrap_index(int(std::floor((x + d.x) * n)), n);
      const int py = wrap_index(int(std::floor((y + d.y) * n)), n);
      sum[size_t(py) * n + px] += energy;
    }
  }
  ImageF out(n, n, 4, 1.0f);
  for (int y = 0; y < n; ++y) {
    for (int x = 0; x < n; ++x) {
      for (int c = 0; c < 3; ++c) out.at(x, y, c) = float(sum[size_t(y) * n + x]);
    }
  }
  return out;
}

}  // namespace aq::reference
