// The numbers one 1D Gaussian pass of the blur needs, computed on the CPU in double so the
// shader only evaluates exp(-i²/2σ²) and multiplies by a normaliser. Handles a kernel wider than
// the image: every tap at distance >= the image length reads the edge texel (clamp-to-edge), so
// those taps are lumped into one "tail" tap per side, which keeps the cost bounded and the
// result exact however large sigma is.
#pragma once

#include <algorithm>
#include <cmath>
#include <vector>

namespace blur {

// Taps reach at least this many sigmas (truncation error per pass below 6.4e-5 of the range).
constexpr double kTruncationSigmas = 4.0;

struct GaussianPass {
  double sigma = 0.0;
  int radius = 0;               // taps -radius..radius are read one by one (or in pairs)
  double inv_two_sigma2 = 0.0;  // weight(i) = exp(-i² · inv_two_sigma2) · norm
  double norm = 1.0;            // 1 / sum of the weights over the truncated kernel
  double tail = 0.0;            // normalised weight of the taps beyond `radius` on one side
  int tail_offset = 0;          // where the tail tap reads: always past the image edge
};

// `length` is the image size along the pass direction.
inline GaussianPass gaussian_pass(double sigma, int length) {
  GaussianPass pass;
  pass.sigma = sigma;
  if (!(sigma > 0.0)) return pass;  // identity: centre tap only
  const int truncation = static_cast<int>(std::ceil(kTruncationSigmas * sigma));
  pass.inv_two_sigma2 = 1.0 / (2.0 * sigma * sigma);
  double sum = 1.0;
  for (int i = 1; i <= truncation; ++i) sum += 2.0 * std::exp(-i * (i * pass.inv_two_sigma2));
  pass.norm = 1.0 / sum;
  // Taps at |i| >= length read the edge texel from every pixel of the image.
  pass.radius = std::min(truncation, std::max(length - 1, 0));
  for (int i = pass.radius + 1; i <= truncation; ++i) {
    pass.tail += std::exp(-i * (i * pass.inv_two_sigma2)) * pass.norm;
  }
  pass.tail_offset = std::max(length, 1);
  return pass;
}

// Entries of blur_gaussian.frag's u_taps table; longer kernels use blur_gaussian_wide.frag.
constexpr size_t kMaxTableTaps = 256;

struct Tap {
  float offset;  // pixels; read at ±offset (the centre tap once)
  float weight;  // per side
};

// The pass as a table: the centre, then single taps or bilinear pairs, then the tail. Weights
// are evaluated in double and rounded once.
inline std::vector<Tap> gaussian_taps(const GaussianPass& pass, bool linear_taps) {
  auto weight = [&](int i) { return std::exp(-i * (i * pass.inv_two_sigma2)) * pass.norm; };
  std::vector<Tap> taps{{0.0f, static_cast<float>(pass.norm)}};
  if (linear_taps) {
    for (int i = 1; i <= pass.radius; i += 2) {
      const double wa = weight(i);
      const double wb = i + 1 <= pass.radius ? weight(i + 1) : 0.0;
      if (wa + wb <= 0.0) break;  // the rest underflows too
      taps.push_back({static_cast<float>(i + wb / (wa + wb)), static_cast<float>(wa + wb)});
    }
  } else {
    for (int i = 1; i <= pass.radius; ++i) {
      taps.push_back({static_cast<float>(i), static_cast<float>(weight(i))});
    }
  }
  if (pass.tail > 0.0) {
    taps.push_back({static_cast<float>(pass.tail_offset), static_cast<float>(pass.tail)});
  }
  return taps;
}

}  // namespace blur
