// The converged caustics reference (exact box-filtered flux per texel): see
// caustics_flux_reference.h.
#include "aquarelle/reference/caustics_flux_reference.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

namespace aq::reference {
namespace {

struct Point {
  double x = 0.0;
  double y = 0.0;
};

// A convex polygon: a triangle clipped by up to four half-planes has at most 7 corners.
struct Polygon {
  std::array<Point, 10> corners;
  int count = 0;
};

double coordinate(const Point& p, int axis) {
  return axis == 0 ? p.x : p.y;
}

// The part of `in` where the coordinate `axis` is >= bound (keep_above) or <= bound.
Polygon clip(const Polygon& in, int axis, double bound, bool keep_above) {
  Polygon out;
  auto inside = [&](const Point& p) {
    return keep_above ? coordinate(p, axis) >= bound : coordinate(p, axis) <= bound;
  };
  for (int i = 0; i < in.count; ++i) {
    const Point& a = in.corners[i];
    const Point& b = in.corners[(i + 1) % in.count];
    const bool a_in = inside(a), b_in = inside(b);
    if (a_in) out.corners[out.count++] = a;
    if (a_in != b_in) {
      const double t = (bound - coordinate(a, axis)) / (coordinate(b, axis) - coordinate(a, axis));
      Point cut{a.x + t * (b.x - a.x), a.y + t * (b.y - a.y)};
      // Exactly on the bound, whatever the rounding of t.
      (axis == 0 ? cut.x : cut.y) = bound;
      out.corners[out.count++] = cut;
    }
  }
  return out;
}

double area_of(const Polygon& polygon) {
  double twice = 0.0;
  for (int i = 0; i < polygon.count; ++i) {
    const Point& a = polygon.corners[i];
    const Point& b = polygon.corners[(i + 1) % polygon.count];
    twice += a.x * b.y - a.y * b.x;
  }
  return 0.5 * std::abs(twice);
}

int wrap_index(int64_t i, int n) {
  const int64_t m = i % n;
  return static_cast<int>(m < 0 ? m + n : m);
}

// Adds `flux` (in texel-intensity units) of the triangle abc (texel units) to the texels it
// overlaps, in proportion to the overlap's area.
void deposit(const Point& a, const Point& b, const Point& c, double flux, int n,
             std::vector<double>& texels) {
  const double min_x = std::min({a.x, b.x, c.x}), max_x = std::max({a.x, b.x, c.x});
  const double min_y = std::min({a.y, b.y, c.y}), max_y = std::max({a.y, b.y, c.y});
  const int64_t x0 = static_cast<int64_t>(std::floor(min_x));
  const int64_t x1 = static_cast<int64_t>(std::floor(max_x));
  const int64_t y0 = static_cast<int64_t>(std::floor(min_y));
  const int64_t y1 = static_cast<int64_t>(std::floor(max_y));
  auto add = [&](int64_t x, int64_t y, double value) {
    texels[static_cast<size_t>(wrap_index(y, n)) * n + wrap_index(x, n)] += value;
  };
  const double area = 0.5 * std::abs((b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x));
  if ((x0 == x1 && y0 == y1) || !(area > 0.0)) {
    // Inside one texel, or degenerate (a fold's edge): all the flux where the triangle is.
    const double cx = (a.x + b.x + c.x) / 3.0, cy = (a.y + b.y + c.y) / 3.0;
    add(static_cast<int64_t>(std::floor(cx)), static_cast<int64_t>(std::floor(cy)), flux);
    return;
  }
  Polygon triangle;
  triangle.corners[0] = a;
  triangle.corners[1] = b;
  triangle.corners[2] = c;
  triangle.count = 3;
  for (int64_t x = x0; x <= x1; ++x) {
    const Polygon column = clip(clip(triangle, 0, double(x), true), 0, double(x + 1), false);
    if (column.count < 3) continue;
    for (int64_t y = y0; y <= y1; ++y) {
      const Polygon cell = clip(clip(column, 1, double(y), true), 1, double(y + 1), false);
      if (cell.count < 3) continue;
      add(x, y, flux * area_of(cell) / area);
    }
  }
}

struct Norms {
  double rms = 0.0;
  double mean_abs = 0.0;
};

Norms difference(const std::vector<double>& a, const std::vector<double>& b) {
  Norms norms;
  for (size_t i = 0; i < a.size(); ++i) {
    const double d = a[i] - b[i];
    norms.rms += d * d;
    norms.mean_abs += std::abs(d);
  }
  norms.rms = std::sqrt(norms.rms / double(a.size()));
  norms.mean_abs /= double(a.size());
  return norms;
}

// Richardson: the error left after the last step, for steps shrinking by 2^-p per halving.
double richardson(double previous_step, double last_step, double* order) {
  if (!(last_step > 0.0)) {
    *order = std::numeric_limits<double>::infinity();
    return 0.0;
  }
  *order = std::log2(previous_step / last_step);
  // Not (yet) converging: the last step is the honest size of the error.
  if (!(*order > 0.5)) return last_step;
  return last_step / (std::exp2(*order) - 1.0);
}

}  // namespace

std::vector<double> caustic_flux_by_coverage(const CausticsParams& params, int grid) {
  const int n = params.resolution;
  const int m = grid;
  std::vector<double> texels(static_cast<size_t>(n) * n, 0.0);
  // Each of the 2 m^2 triangles carries 1/(2 m^2) of the tile's light; a texel's intensity is
  // its light divided by its area 1/n^2.
  const double flux = double(n) * n / (2.0 * double(m) * m);
  // Refracted vertices of two grid rows, in texel units; the grid is periodic (vertex m is
  // vertex 0 moved by one tile).
  auto refracted_row = [&](int j, std::vector<Point>& row) {
    for (int i = 0; i <= m; ++i) {
      const Displacement d = floor_displacement(double(i % m) / m, double(j % m) / m, params);
      row[i] = {(double(i) / m + d.x) * n, (double(j) / m + d.y) * n};
    }
  };
  std::vector<Point> below(m + 1), above(m + 1);
  refracted_row(0, below);
  for (int j = 0; j < m; ++j) {
    refracted_row(j + 1, above);
    for (int i = 0; i < m; ++i) {
      deposit(below[i], below[i + 1], above[i + 1], flux, n, texels);
      deposit(below[i], above[i + 1], above[i], flux, n, texels);
    }
    std::swap(below, above);
  }
  return texels;
}

ImageF to_caustic_image(const std::vector<double>& texels, int resolution) {
  ImageF out(resolution, resolution, 4, 1.0f);
  for (int y = 0; y < resolution; ++y) {
    for (int x = 0; x < resolution; ++x) {
      const float value = static_cast<float>(texels[static_cast<size_t>(y) * resolution + x]);
      for (int c = 0; c < 3; ++c) out.at(x, y, c) = value;
    }
  }
  return out;
}

ImageF caustics_by_coverage(const CausticsParams& params, int grid) {
  return to_caustic_image(caustic_flux_by_coverage(params, grid), params.resolution);
}

CausticConvergence converge_caustic_flux(const CausticsParams& params, int finest_grid,
                                         int levels) {
  CausticConvergence result;
  levels = std::max(levels, 3);
  std::vector<double> previous;
  std::vector<Norms> steps;
  for (int k = levels - 1; k >= 0; --k) {
    const int grid = std::max(1, finest_grid >> k);
    std::vector<double> texels = caustic_flux_by_coverage(params, grid);
    if (!previous.empty()) {
      steps.push_back(difference(texels, previous));
      result.rms_steps.push_back(steps.back().rms);
      result.mean_abs_steps.push_back(steps.back().mean_abs);
    }
    result.grids.push_back(grid);
    previous = std::move(texels);
  }
  const Norms& before = steps[steps.size() - 2];
  const Norms& last = steps.back();
  double mean_abs_order = 0.0;
  result.rms_error = richardson(before.rms, last.rms, &result.order);
  result.mean_abs_error = richardson(before.mean_abs, last.mean_abs, &mean_abs_order);
  result.texels = std::move(previous);
  return result;
}

}  // namespace aq::reference
