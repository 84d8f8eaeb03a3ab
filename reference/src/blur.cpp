// CPU references of the `blur` node: see blur.h.
#include "aquarelle/reference/blur.h"

#include <algorithm>
#include <cmath>

namespace aq::reference {
namespace {

int clamp_index(int i, int n) {
  return std::clamp(i, 0, n - 1);
}

// A 4-channel double image, so that chained passes round only once, at the end.
struct ImageD {
  int width, height;
  std::vector<double> data;
  ImageD(int w, int h) : width(w), height(h), data(static_cast<size_t>(w) * h * 4, 0.0) {}
  double& at(int x, int y, int c) { return data[(static_cast<size_t>(y) * width + x) * 4 + c]; }
  double at(int x, int y, int c) const {
    return data[(static_cast<size_t>(y) * width + x) * 4 + c];
  }
};

ImageD to_double(const ImageF& image) {
  ImageD out(image.width, image.height);
  for (int y = 0; y < image.height; ++y)
    for (int x = 0; x < image.width; ++x)
      for (int c = 0; c < 4; ++c) out.at(x, y, c) = c < image.channels ? image.at(x, y, c) : 1.0;
  return out;
}

ImageF to_float(const ImageD& image) {
  ImageF out(image.width, image.height, 4);
  for (size_t i = 0; i < image.data.size(); ++i) out.pixels[i] = static_cast<float>(image.data[i]);
  return out;
}

ImageD blur_double(const ImageD& image, double sigma, double truncation_sigmas) {
  const std::vector<double> k = gaussian_kernel(sigma, truncation_sigmas);
  const int r = static_cast<int>(k.size()) - 1;
  ImageD horizontal(image.width, image.height);
  for (int y = 0; y < image.height; ++y)
    for (int x = 0; x < image.width; ++x)
      for (int c = 0; c < 4; ++c) {
        double sum = 0.0;
        for (int i = -r; i <= r; ++i)
          sum += k[std::abs(i)] * image.at(clamp_index(x + i, image.width), y, c);
        horizontal.at(x, y, c) = sum;
      }
  ImageD out(image.width, image.height);
  for (int y = 0; y < image.height; ++y)
    for (int x = 0; x < image.width; ++x)
      for (int c = 0; c < 4; ++c) {
        double sum = 0.0;
        for (int i = -r; i <= r; ++i)
          sum += k[std::abs(i)] * horizontal.at(x, clamp_index(y + i, image.height), c);
        out.at(x, y, c) = sum;
      }
  return out;
}

// Bilinear read at continuous pixel coordinates (pixel centres at integers), clamp-to-edge.
double bilinear(const ImageD& image, double x, double y, int c) {
  const double fx = std::floor(x), fy = std::floor(y);
  const double tx = x - fx, ty = y - fy;
  const int x0 = static_cast<int>(fx), y0 = static_cast<int>(fy);
  auto texel = [&](int xi, int yi) {
    return image.at(clamp_index(xi, image.width), clamp_index(yi, image.height), c);
  };
  return (1 - ty) * ((1 - tx) * texel(x0, y0) + tx * texel(x0 + 1, y0)) +
         ty * ((1 - tx) * texel(x0, y0 + 1) + tx * texel(x0 + 1, y0 + 1));
}

}  // namespace

std::vector<double> gaussian_kernel(double sigma, double truncation_sigmas) {
  if (!(sigma > 0.0)) return {1.0};
  const int r = static_cast<int>(std::ceil(truncation_sigmas * sigma));
  std::vector<double> k(r + 1);
  double sum = 0.0;
  for (int i = 0; i <= r; ++i) {
    k[i] = std::exp(-0.5 * (i / sigma) * (i / sigma));
    sum += i == 0 ? k[i] : 2.0 * k[i];
  }
  for (double& w : k) w /= sum;
  return k;
}

ImageF gaussian_blur(const ImageF& image, double sigma, double truncation_sigmas) {
  return to_float(blur_double(to_double(image), sigma, truncation_sigmas));
}

double blur_strength(int x, int y, int width, int height, const ImageF* depth,
                     const BlurParams& params) {
  double depth_term = 1.0;
  if (depth != nullptr) {
    const double z = depth->at(x, y, 0);
    if (std::isfinite(z) && z > 0.0)
      depth_term = std::pow(std::min(z / params.distance_scale, 1.0), 3);
  }
  // Squared distance from the centre over the squared distance to a corner.
  const double dx = x + 0.5 - 0.5 * width, dy = y + 0.5 - 0.5 * height;
  const double radial_term =
      (dx * dx + dy * dy) / (0.25 * (double(width) * width + double(height) * height));
  return std::clamp(params.depth_weight * depth_term + params.radial_weight * radial_term, 0.0,
                    1.0);
}

ImageF stacked_blur(const ImageF& image, const ImageF* depth, const BlurParams& params) {
  const double max_sigma = params.sigma * std::min(1.0, params.depth_weight + params.radial_weight);
  const double ratio = std::pow(2.0, 1.0 / params.levels_per_octave);
  std::vector<double> sigmas{max_sigma};
  while (sigmas.size() < 12 && sigmas.back() / ratio >= 0.5)
    sigmas.push_back(sigmas.back() / ratio);
  sigmas.push_back(0.0);
  std::reverse(sigmas.begin(), sigmas.end());
  const ImageD input = to_double(image);
  std::vector<ImageD> levels{input};
  for (size_t k = 1; k < sigmas.size(); ++k) levels.push_back(blur_double(input, sigmas[k], 8.0));

  ImageD out(image.width, image.height);
  for (int y = 0; y < image.height; ++y)
    for (int x = 0; x < image.width; ++x) {
      const double sigma =
          params.sigma * blur_strength(x, y, image.width, image.height, depth, params);
      size_t a = 0;
      double t = 0.0;
      if (sigma >= sigmas.back()) {
        a = sigmas.size() - 1;
      } else {
        while (a + 2 < sigmas.size() && sigmas[a + 1] < sigma) ++a;
        t = (sigma * sigma - sigmas[a] * sigmas[a]) /
            (sigmas[a + 1] * sigmas[a + 1] - sigmas[a] * sigmas[a]);
      }
      for (int c = 0; c < 4; ++c) {
        const double lo = levels[a].at(x, y, c);
        out.at(x, y, c) = t > 0.0 ? lo + t * (levels[a + 1].at(x, y, c) - lo) : lo;
      }
    }
  return to_float(out);
}

ImageF exact_variable_blur(const ImageF& image, const ImageF* depth, const BlurParams& params) {
  const ImageD input = to_double(image);
  ImageD out(image.width, image.height);
  for (int y = 0; y < image.height; ++y)
    for (int x = 0; x < image.width; ++x) {
      const double sigma =
          params.sigma * blur_strength(x, y, image.width, image.height, depth, params);
      const std::vector<double> k = gaussian_kernel(sigma, 8.0);
      const int r = static_cast<int>(k.size()) - 1;
      for (int c = 0; c < 4; ++c) {
        double sum = 0.0;
        for (int j = -r; j <= r; ++j) {
          double row = 0.0;
          for (int i = -r; i <= r; ++i)
            row += k[std::abs(i)] *
                   input.at(clamp_index(x + i, image.width), clamp_index(y + j, image.height), c);
          sum += k[std::abs(j)] * row;
        }
        out.at(x, y, c) = sum;
      }
    }
  return to_float(out);
}

int direct_blur_radius(double max_sigma) {
  return 2 * std::max(1, static_cast<int>(std::ceil(max_sigma - 1e-9)));
}

ImageF truncated_variable_blur(const ImageF& image, const ImageF* depth, const BlurParams& params,
                               int radius) {
  const ImageD input = to_double(image);
  ImageD out(image.width, image.height);
  std::vector<double> k(radius + 1);
  for (int y = 0; y < image.height; ++y)
    for (int x = 0; x < image.width; ++x) {
      const double sigma =
          params.sigma * blur_strength(x, y, image.width, image.height, depth, params);
      // exp(-i²/2σ²) for |i| <= radius, normalised over the 2·radius + 1 taps.
      double sum_k = 0.0;
      for (int i = 0; i <= radius; ++i) {
        k[i] = i == 0 ? 1.0 : sigma > 0.0 ? std::exp(-0.5 * (i / sigma) * (i / sigma)) : 0.0;
        sum_k += i == 0 ? k[i] : 2.0 * k[i];
      }
      for (int c = 0; c < 4; ++c) {
        double sum = 0.0;
        for (int j = -radius; j <= radius; ++j) {
          double row = 0.0;
          for (int i = -radius; i <= radius; ++i)
            row += k[std::abs(i)] *
                   input.at(clamp_index(x + i, image.width), clamp_index(y + j, image.height), c);
          sum += k[std::abs(j)] * row;
        }
        out.at(x, y, c) = sum / (sum_k * sum_k);
      }
    }
  return to_float(out);
}

ImageF separable_variable_blur(const ImageF& image, const ImageF* depth, const BlurParams& params,
                               int radius) {
  const ImageD input = to_double(image);
  // The normalised 1D kernel exp(-i²/2σ²), |i| <= radius, of pixel (x, y)'s own σ.
  auto kernel = [&](int x, int y) {
    const double sigma =
        params.sigma * blur_strength(x, y, image.width, image.height, depth, params);
    std::vector<double> k(radius + 1);
    double sum = 0.0;
    for (int i = 0; i <= radius; ++i) {
      k[i] = i == 0 ? 1.0 : sigma > 0.0 ? std::exp(-0.5 * (i / sigma) * (i / sigma)) : 0.0;
      sum += i == 0 ? k[i] : 2.0 * k[i];
    }
    for (double& w : k) w /= sum;
    return k;
  };
  // Rows first, each pixel with its own σ; then columns, each pixel with its own σ.
  ImageD rows(image.width, image.height);
  for (int y = 0; y < image.height; ++y)
    for (int x = 0; x < image.width; ++x) {
      const std::vector<double> k = kernel(x, y);
      for (int c = 0; c < 4; ++c) {
        double sum = 0.0;
        for (int i = -radius; i <= radius; ++i)
          sum += k[std::abs(i)] * input.at(clamp_index(x + i, image.width), y, c);
        rows.at(x, y, c) = sum;
      }
    }
  ImageD out(image.width, image.height);
  for (int y = 0; y < image.height; ++y)
    for (int x = 0; x < image.width; ++x) {
      const std::vector<double> k = kernel(x, y);
      for (int c = 0; c < 4; ++c) {
        double sum = 0.0;
        for (int j = -radius; j <= radius; ++j)
          sum += k[std::abs(j)] * rows.at(x, clamp_index(y + j, image.height), c);
        out.at(x, y, c) = sum;
      }
    }
  return to_float(out);
}

ImageF pinwheel_variable_blur(const ImageF& image, const ImageF* depth, const BlurParams& params) {
  auto kept = [](int i, int j) {
    if (std::abs(i) == 2 && std::abs(j) == 2) return false;
    return !((i == -2 && j == 1) || (i == 1 && j == 2) || (i == 2 && j == -1) ||
             (i == -1 && j == -2));
  };
  const ImageD input = to_double(image);
  ImageD out(image.width, image.height);
  for (int y = 0; y < image.height; ++y)
    for (int x = 0; x < image.width; ++x) {
      const double sigma =
          params.sigma * blur_strength(x, y, image.width, image.height, depth, params);
      auto g = [&](int i) {
        return i == 0 ? 1.0 : sigma > 0.0 ? std::exp(-0.5 * (i / sigma) * (i / sigma)) : 0.0;
      };
      double total = 0.0;
      double sum[4] = {0, 0, 0, 0};
      for (int j = -2; j <= 2; ++j)
        for (int i = -2; i <= 2; ++i) {
          if (!kept(i, j)) continue;
          const double w = g(i) * g(j);
          if (w == 0.0) continue;
          total += w;
          for (int c = 0; c < 4; ++c)
            sum[c] +=
                w * input.at(clamp_index(x + i, image.width), clamp_index(y + j, image.height), c);
        }
      for (int c = 0; c < 4; ++c) out.at(x, y, c) = sum[c] / total;
    }
  return to_float(out);
}

ImageF strided_blur(const ImageF& image, const ImageF* depth, const BlurParams& params) {
  const ImageD input = to_double(image);
  const double binomial[5] = {1, 4, 6, 4, 1};
  auto strided = [&](int x, int y, int c, double stride) {
    double sum = 0.0;
    for (int j = 0; j < 5; ++j)
      for (int i = 0; i < 5; ++i)
        sum += binomial[i] * binomial[j] *
               bilinear(input, x + (i - 2) * stride, y + (j - 2) * stride, c);
    return sum / 256.0;
  };
  ImageD out(image.width, image.height);
  for (int y = 0; y < image.height; ++y)
    for (int x = 0; x < image.width; ++x) {
      const double s = blur_strength(x, y, image.width, image.height, depth, params);
      for (int c = 0; c < 4; ++c) {
        const double sharp = input.at(x, y, c);
        if (s <= 0.0) {
          out.at(x, y, c) = sharp;
        } else if (s <= 0.5) {
          out.at(x, y, c) = sharp + 2 * s * (strided(x, y, c, 0.3 * params.sigma) - sharp);
        } else {
          const double a = strided(x, y, c, 0.3 * params.sigma);
          out.at(x, y, c) = a + (2 * s - 1) * (strided(x, y, c, params.sigma) - a);
        }
      }
    }
  return to_float(out);
}

}  // namespace aq::reference
