// Speed-against-error plot of `aquarelle bench` (see bench_plot.h). Coordinates are in pixels
// with y up, as ImageF stores rows (row 0 at the bottom).
#include "bench_plot.h"

#include <aquarelle/core/image_io.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <limits>

namespace aq::app {

namespace {

using Color = std::array<float, 3>;

// A 5x7 bitmap font: seven rows top to bottom, bit 4 is the leftmost column. Letters are
// upper case; lower case is drawn with them.
struct Glyph {
  char c;
  uint8_t rows[7];
};
constexpr Glyph kFont[] = {
    {'0', {0x0E, 0x11, 0x13, 0x15, 0x19, 0x11, 0x0E}},
    {'1', {0x04, 0x0C, 0x04, 0x04, 0x04, 0x04, 0x0E}},
    {'2', {0x0E, 0x11, 0x01, 0x02, 0x04, 0x08, 0x1F}},
    {'3', {0x1F, 0x02, 0x04, 0x02, 0x01, 0x11, 0x0E}},
    {'4', {0x02, 0x06, 0x0A, 0x12, 0x1F, 0x02, 0x02}},
    {'5', {0x1F, 0x10, 0x1E, 0x01, 0x01, 0x11, 0x0E}},
    {'6', {0x06, 0x08, 0x10, 0x1E, 0x11, 0x11, 0x0E}},
    {'7', {0x1F, 0x01, 0x02, 0x04, 0x08, 0x08, 0x08}},
    {'8', {0x0E, 0x11, 0x11, 0x0E, 0x11, 0x11, 0x0E}},
    {'9', {0x0E, 0x11, 0x11, 0x0F, 0x01, 0x02, 0x0C}},
    {'A', {0x0E, 0x11, 0x11, 0x1F, 0x11, 0x11, 0x11}},
    {'B', {0x1E, 0x11, 0x11, 0x1E, 0x11, 0x11, 0x1E}},
    {'C', {0x0E, 0x11, 0x10, 0x10, 0x10, 0x11, 0x0E}},
    {'D', {0x1C, 0x12, 0x11, 0x11, 0x11, 0x12, 0x1C}},
    {'E', {0x1F, 0x10, 0x10, 0x1E, 0x10, 0x10, 0x1F}},
    {'F', {0x1F, 0x10, 0x10, 0x1E, 0x10, 0x10, 0x10}},
    {'G', {0x0E, 0x11, 0x10, 0x17, 0x11, 0x11, 0x0F}},
    {'H', {0x11, 0x11, 0x11, 0x1F, 0x11, 0x11, 0x11}},
    {'I', {0x0E, 0x04, 0x04, 0x04, 0x04, 0x04, 0x0E}},
    {'J', {0x07, 0x02, 0x02, 0x02, 0x02, 0x12, 0x0C}},
    {'K', {0x11, 0x12, 0x14, 0x18, 0x14, 0x12, 0x11}},
    {'L', {0x10, 0x10, 0x10, 0x10, 0x10, 0x10, 0x1F}},
    {'M', {0x11, 0x1B, 0x15, 0x15, 0x11, 0x11, 0x11}},
    {'N', {0x11, 0x11, 0x19, 0x15, 0x13, 0x11, 0x11}},
    {'O', {0x0E, 0x11, 0x11, 0x11, 0x11, 0x11, 0x0E}},
    {'P', {0x1E, 0x11, 0x11, 0x1E, 0x10, 0x10, 0x10}},
    {'Q', {0x0E, 0x11, 0x11, 0x11, 0x15, 0x12, 0x0D}},
    {'R', {0x1E, 0x11, 0x11, 0x1E, 0x14, 0x12, 0x11}},
    {'S', {0x0F, 0x10, 0x10, 0x0E, 0x01, 0x01, 0x1E}},
    {'T', {0x1F, 0x04, 0x04, 0x04, 0x04, 0x04, 0x04}},
    {'U', {0x11, 0x11, 0x11, 0x11, 0x11, 0x11, 0x0E}},
    {'V', {0x11, 0x11, 0x11, 0x11, 0x11, 0x0A, 0x04}},
    {'W', {0x11, 0x11, 0x11, 0x15, 0x15, 0x15, 0x0A}},
    {'X', {0x11, 0x11, 0x0A, 0x04, 0x0A, 0x11, 0x11}},
    {'Y', {0x11, 0x11, 0x11, 0x0A, 0x04, 0x04, 0x04}},
    {'Z', {0x1F, 0x01, 0x02, 0x04, 0x08, 0x10, 0x1F}},
    {'.', {0x00, 0x00, 0x00, 0x00, 0x00, 0x0C, 0x0C}},
    {',', {0x00, 0x00, 0x00, 0x00, 0x0C, 0x04, 0x08}},
    {'-', {0x00, 0x00, 0x00, 0x1F, 0x00, 0x00, 0x00}},
    {'+', {0x00, 0x04, 0x04, 0x1F, 0x04, 0x04, 0x00}},
    {'=', {0x00, 0x00, 0x1F, 0x00, 0x1F, 0x00, 0x00}},
    {'(', {0x02, 0x04, 0x08, 0x08, 0x08, 0x04, 0x02}},
    {')', {0x08, 0x04, 0x02, 0x02, 0x02, 0x04, 0x08}},
    {'/', {0x00, 0x01, 0x02, 0x04, 0x08, 0x10, 0x00}},
    {'_', {0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x1F}},
    {':', {0x00, 0x0C, 0x0C, 0x00, 0x0C, 0x0C, 0x00}},
    {'<', {0x02, 0x04, 0x08, 0x10, 0x08, 0x04, 0x02}},
    {'>', {0x08, 0x04, 0x02, 0x01, 0x02, 0x04, 0x08}},
};

const Glyph* find_glyph(char c) {
  if (c >= 'a' && c <= 'z') c = static_cast<char>(c - 'a' + 'A');
  for (const auto& glyph : kFont) {
    if (glyph.c == c) return &glyph;
  }
  return nullptr;  // drawn as a space
}

// Distinct colours for the curves (Okabe-Ito, then others).
constexpr Color kPalette[] = {{0.00f, 0.45f, 0.70f}, {0.90f, 0.60f, 0.00f}, {0.00f, 0.62f, 0.45f},
                              {0.80f, 0.40f, 0.00f}, {0.80f, 0.47f, 0.65f}, {0.34f, 0.71f, 0.91f},
                              {0.60f, 0.10f, 0.10f}, {0.30f, 0.30f, 0.30f}, {0.45f, 0.45f, 0.00f},
                              {0.35f, 0.00f, 0.55f}, {0.55f, 0.35f, 0.15f}, {0.00f, 0.35f, 0.35f},
                              {0.95f, 0.35f, 0.55f}, {0.50f, 0.70f, 0.20f}};
constexpr Color kBlack{0.0f, 0.0f, 0.0f};
constexpr Color kGrid{0.85f, 0.85f, 0.85f};

class Canvas {
 public:
  Canvas(int width, int height) : image_(width, height, 4, 1.0f) {}

  void pixel(int x, int y, const Color& color) {
    if (x < 0 || y < 0 || x >= image_.width || y >= image_.height) return;
    for (int c = 0; c < 3; ++c) image_.at(x, y, c) = color[c];
  }
  void rect(int x0, int y0, int x1, int y1, const Color& color, bool filled) {
    for (int y = y0; y <= y1; ++y) {
      for (int x = x0; x <= x1; ++x) {
        if (filled || x == x0 || x == x1 || y == y0 || y == y1) pixel(x, y, color);
      }
    }
  }
  // Bresenham, `thickness` pixels wide.
  void line(int x0, int y0, int x1, int y1, const Color& color, int thickness = 1) {
    const int dx = std::abs(x1 - x0), dy = -std::abs(y1 - y0);
    const int sx = x0 < x1 ? 1 : -1, sy = y0 < y1 ? 1 : -1;
    int error = dx + dy;
    for (;;) {
      for (int t = 0; t < thickness; ++t) {
        for (int u = 0; u < thickness; ++u)
          pixel(x0 + t - thickness / 2, y0 + u - thickness / 2, color);
      }
      if (x0 == x1 && y0 == y1) break;
      const int e2 = 2 * error;
      if (e2 >= dy) {
        error += dy;
        x0 += sx;
      }
      if (e2 <= dx) {
        error += dx;
        y0 += sy;
      }
    }
  }
  // Text whose top-left corner is (x, top); each font pixel is scale x scale.
  void text(int x, int top, const std::string& s, const Color& color, int scale = 2) {
    for (char c : s) {
      if (const Glyph* glyph = find_glyph(c)) {
        for (int row = 0; row < 7; ++row) {
          for (int col = 0; col < 5; ++col) {
            if ((glyph->rows[row] >> (4 - col) & 1) == 0) continue;
            rect(x + col * scale, top - (row + 1) * scale + 1, x + (col + 1) * scale - 1,
                 top - row * scale, color, true);
          }
        }
      }
      x += 6 * scale;
    }
  }
  static int text_width(const std::string& s, int scale = 2) {
    return static_cast<int>(s.size()) * 6 * scale;
  }
  ImageF take() { return std::move(image_); }

 private:
  ImageF image_;
};

std::string decade_label(int exponent) {
  if (exponent >= 0 && exponent <= 3)
    return std::to_string(static_cast<int>(std::pow(10, exponent)));
  if (exponent == -1) return "0.1";
  if (exponent == -2) return "0.01";
  return "1e" + std::to_string(exponent);
}

}  // namespace

std::vector<size_t> pareto_points(const Sweep& sweep) {
  std::vector<size_t> order(sweep.points.size());
  for (size_t i = 0; i < order.size(); ++i) order[i] = i;
  std::sort(order.begin(), order.end(), [&](size_t a, size_t b) {
    const auto& pa = sweep.points[a];
    const auto& pb = sweep.points[b];
    if (pa.time_ms.median != pb.time_ms.median) return pa.time_ms.median < pb.time_ms.median;
    return pa.error.mean_abs < pb.error.mean_abs;
  });
  std::vector<size_t> front;
  double best = std::numeric_limits<double>::infinity();
  for (size_t i : order) {
    const double error = sweep.points[i].error.mean_abs;
    if (error < best) {
      front.push_back(i);
      best = error;
    }
  }
  return front;
}

ImageF draw_plot(const std::vector<Sweep>& sweeps, const std::string& title) {
  // The legend is as wide as its longest label, so no series name is cut off.
  int legend_width = Canvas::text_width("hollow: other");
  for (const auto& sweep : sweeps) {
    legend_width = std::max(legend_width, Canvas::text_width(sweep.series) + 18);
  }
  const int width = 740 + legend_width + 40, height = 640;
  const int left = 90, right = 740, bottom = 70, top = height - 50;
  Canvas canvas(width, height);

  // Axis ranges in decades, from the points; errors of exactly 0 sit on a floor line.
  double min_t = std::numeric_limits<double>::infinity(), max_t = 0;
  double min_e = std::numeric_limits<double>::infinity(), max_e = 0;
  bool any_exact = false;
  for (const auto& sweep : sweeps) {
    for (const auto& p : sweep.points) {
      if (!(p.time_ms.median > 0) || !std::isfinite(p.error.mean_abs)) continue;
      min_t = std::min(min_t, p.time_ms.median);
      max_t = std::max(max_t, p.time_ms.median);
      if (p.error.mean_abs > 0) {
        min_e = std::min(min_e, p.error.mean_abs);
        max_e = std::max(max_e, p.error.mean_abs);
      } else {
        any_exact = true;
      }
    }
  }
  if (!(max_t > 0)) min_t = 0.1, max_t = 10;
  if (!(max_e > 0)) min_e = 1e-4, max_e = 1e-1;
  const int t0 = static_cast<int>(std::floor(std::log10(min_t)));
  const int t1 = std::max(t0 + 1, static_cast<int>(std::ceil(std::log10(max_t))));
  // One decade below the smallest error holds the "exact" line when some point is exact.
  const int e0 = static_cast<int>(std::floor(std::log10(min_e))) - (any_exact ? 1 : 0);
  const int e1 = std::max(e0 + 1, static_cast<int>(std::ceil(std::log10(max_e))));
  auto px = [&](double t) {
    return left + static_cast<int>(std::lround((std::log10(t) - t0) / (t1 - t0) * (right - left)));
  };
  auto py = [&](double e) {
    const double decade = e > 0 ? std::log10(e) : e0;
    return bottom + static_cast<int>(std::lround((std::max(decade, double(e0)) - e0) / (e1 - e0) *
                                                 (top - bottom)));
  };

  // Grid, ticks and labels.
  for (int d = t0; d <= t1; ++d) {
    const int x = px(std::pow(10.0, d));
    canvas.line(x, bottom, x, top, kGrid);
    const std::string label = decade_label(d);
    canvas.text(x - Canvas::text_width(label) / 2, bottom - 8, label, kBlack);
  }
  for (int d = e0; d <= e1; ++d) {
    const int y = py(std::pow(10.0, d));
    canvas.line(left, y, right, y, kGrid);
    const std::string label = (any_exact && d == e0) ? "exact" : decade_label(d);
    canvas.text(left - 8 - Canvas::text_width(label), y + 7, label, kBlack);
  }
  canvas.line(left, bottom, right, bottom, kBlack, 2);
  canvas.line(left, bottom, left, top, kBlack, 2);
  canvas.text(left + (right - left) / 2 - Canvas::text_width("time ms") / 2, bottom - 32, "time ms",
              kBlack);
  canvas.text(left - 80, top + 30, "mean abs error", kBlack);
  canvas.text(left + 150, height - 8, title, kBlack);

  // Curves: every point hollow, the Pareto front filled and joined.
  int legend_top = top;
  for (size_t s = 0; s < sweeps.size(); ++s) {
    const Sweep& sweep = sweeps[s];
    const Color& color = kPalette[s % std::size(kPalette)];
    for (const auto& p : sweep.points) {
      if (!(p.time_ms.median > 0) || !std::isfinite(p.error.mean_abs)) continue;
      const int x = px(p.time_ms.median), y = py(p.error.mean_abs);
      canvas.rect(x - 4, y - 4, x + 4, y + 4, color, false);
    }
    int last_x = -1, last_y = -1;
    for (size_t i : pareto_points(sweep)) {
      const auto& p = sweep.points[i];
      if (!(p.time_ms.median > 0) || !std::isfinite(p.error.mean_abs)) continue;
      const int x = px(p.time_ms.median), y = py(p.error.mean_abs);
      if (last_x >= 0) canvas.line(last_x, last_y, x, y, color, 2);
      canvas.rect(x - 4, y - 4, x + 4, y + 4, color, true);
      last_x = x;
      last_y = y;
    }
    canvas.rect(right + 20, legend_top - 12, right + 30, legend_top - 2, color, true);
    canvas.text(right + 38, legend_top, sweep.series, kBlack);
    legend_top -= 22;
  }
  canvas.text(right + 20, legend_top - 10, "filled: pareto", kBlack);
  canvas.text(right + 20, legend_top - 32, "hollow: other", kBlack);
  return canvas.take();
}

Status write_plot(const std::vector<Sweep>& sweeps, const std::string& title,
                  const std::string& path) {
  return write_image(path, draw_plot(sweeps, title));
}

}  // namespace aq::app
