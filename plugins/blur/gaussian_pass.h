// The numbers one 1D Gaussian pass of the blur needs, computed on the CPU in double so the
// shader only evaluates exp(-i²/2σ²) and multiplies by a normaliser. Handles a kernel wider than
// the image: every tap at distance >= the image length reads the edge texel (clamp-to-edge), so
// those taps are lumped into one "tail" tap per side, which keeps the cost bounded and the
// result exact however large sigma is.
#pragma once

#include <algorithm>
#include <cmath>

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

}  // namespace blur
