// CPU reference of the `bleed` node: see bleed.h.
#include "aquarelle/reference/bleed.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

namespace aq::reference {
namespace {

using Pixel = std::array<double, 4>;

struct Field {
  int width = 0, height = 0;
  std::vector<Pixel> colour;
  std::vector<double> amount, depth, id;
  size_t at(int x, int y) const { return static_cast<size_t>(y) * width + x; }
};

bool finite(const Pixel& c) {
  return std::all_of(c.begin(), c.end(), [](double v) { return std::isfinite(v); });
}

double clamped_bleed(double b) {
  return b > 0.0 ? std::min(b, 1.0) : 0.0;
}

Field initial(const ImageF& image, const ImageF& control, const ImageF* depth, const ImageF* id,
              double amount) {
  Field f;
  f.width = image.width;
  f.height = image.height;
  const size_t n = static_cast<size_t>(f.width) * f.height;
  f.colour.resize(n);
  f.amount.resize(n);
  f.depth.assign(n, 0.0);
  f.id.assign(n, 0.0);
  for (int y = 0; y < f.height; ++y)
    for (int x = 0; x < f.width; ++x) {
      const size_t i = f.at(x, y);
      for (int c = 0; c < 4; ++c) f.colour[i][c] = c < image.channels ? image.at(x, y, c) : 1.0;
      const int cx = std::min(x, control.width - 1), cy = std::min(y, control.height - 1);
      f.amount[i] =
          clamped_bleed(static_cast<double>(control.at(cx, cy, 0)) * static_cast<float>(amount));
      if (depth)
        f.depth[i] = depth->at(std::min(x, depth->width - 1), std::min(y, depth->height - 1), 0);
      if (id) f.id[i] = id->at(std::min(x, id->width - 1), std::min(y, id->height - 1), 0);
    }
  return f;
}

bool may_run(const Field& f, size_t from, size_t into, double bias) {
  return f.id[from] == f.id[into] || f.depth[from] <= f.depth[into] + bias;
}

int radius_of(const BleedParams& p, int width, int height) {
  return std::clamp(static_cast<int>(std::ceil(p.reach * p.sigma)), 1, std::max(width, height));
}

// One gated 1D pass along (dx, dy); returns the blurred colours and the largest amounts.
Field pass(const Field& in, int dx, int dy, const BleedParams& p) {
  Field out = in;
  const int radius = radius_of(p, in.width, in.height);
  for (int y = 0; y < in.height; ++y)
    for (int x = 0; x < in.width; ++x) {
      const size_t into = in.at(x, y);
      Pixel sum{0, 0, 0, 0};
      double weights = 0.0, amount = 0.0;
      for (int i = -radius; i <= radius; ++i) {
        const int sx = std::clamp(x + i * dx, 0, in.width - 1);
        const int sy = std::clamp(y + i * dy, 0, in.height - 1);
        const size_t from = in.at(sx, sy);
        if (!may_run(in, from, into, p.depth_bias) || !finite(in.colour[from])) continue;
        const double w = std::exp(-double(i) * i / (2.0 * p.sigma * p.sigma));
        for (int c = 0; c < 4; ++c) sum[c] += w * in.colour[from][c];
        weights += w;
        amount = std::max(amount, in.amount[from]);
      }
      if (weights > 0.0) {
        for (int c = 0; c < 4; ++c) out.colour[into][c] = sum[c] / weights;
      }
      out.amount[into] = amount;
    }
  return out;
}

ImageF finish(const ImageF& image, const Field& blurred) {
  ImageF out = image;
  for (int y = 0; y < image.height; ++y)
    for (int x = 0; x < image.width; ++x) {
      const size_t i = blurred.at(x, y);
      const double a = blurred.amount[i];
      if (!(a > 0.0)) continue;
      for (int c = 0; c < image.channels; ++c) {
        const double v = image.at(x, y, c);
        out.at(x, y, c) = static_cast<float>(v * (1.0 - a) + blurred.colour[i][c] * a);
      }
    }
  return out;
}

}  // namespace

ImageF bleed(const ImageF& image, const ImageF& control, const ImageF* depth, const ImageF* id,
             const BleedParams& params) {
  if (!(params.sigma > 0.0) || !(params.amount > 0.0)) return image;
  const Field start = initial(image, control, depth, id, params.amount);
  return finish(image, pass(pass(start, 1, 0, params), 0, 1, params));
}

ImageF bleed_2d(const ImageF& image, const ImageF& control, const ImageF* depth, const ImageF* id,
                const BleedParams& params) {
  if (!(params.sigma > 0.0) || !(params.amount > 0.0)) return image;
  const Field in = initial(image, control, depth, id, params.amount);
  Field out = in;
  const int radius = radius_of(params, in.width, in.height);
  for (int y = 0; y < in.height; ++y)
    for (int x = 0; x < in.width; ++x) {
      const size_t into = in.at(x, y);
      Pixel sum{0, 0, 0, 0};
      double weights = 0.0, amount = 0.0;
      for (int j = -radius; j <= radius; ++j)
        for (int i = -radius; i <= radius; ++i) {
          const size_t from =
              in.at(std::clamp(x + i, 0, in.width - 1), std::clamp(y + j, 0, in.height - 1));
          if (!may_run(in, from, into, params.depth_bias) || !finite(in.colour[from])) continue;
          const double w = std::exp(-double(i * i + j * j) / (2.0 * params.sigma * params.sigma));
          for (int c = 0; c < 4; ++c) sum[c] += w * in.colour[from][c];
          weights += w;
          amount = std::max(amount, in.amount[from]);
        }
      if (weights > 0.0) {
        for (int c = 0; c < 4; ++c) out.colour[into][c] = sum[c] / weights;
      }
      out.amount[into] = amount;
    }
  return finish(image, out);
}

}  // namespace aq::reference
