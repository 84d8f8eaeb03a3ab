// CPU references of the `blur` node in double precision, written from the maths in
// plugins/blur/README.md: the exact clamp-to-edge Gaussian, the per-pixel strength, the stack
// of exact blurs mixed by variance, a per-pixel exact variable Gaussian (the ideal the stack
// approximates), its truncation at a fixed radius (the one-pass path for a small σmax) and the
// seed's strided 5×5 kernel. Used by the tests and `aquarelle bench`.
#pragma once

#include <aquarelle/core/image.h>

#include <vector>

namespace aq::reference {

struct BlurParams {
  double sigma = 4.0;  // pixels, at strength 1
  double distance_scale = 20.0;
  double depth_weight = 1.0;
  double radial_weight = 0.35;
  int levels_per_octave = 1;  // stack density of the varying-σ `gaussian` method
};

// Sampled Gaussian exp(-i²/2σ²) for i = 0..ceil(truncation_sigmas·σ), normalised so that the
// symmetric kernel sums to 1. σ <= 0 gives {1}.
std::vector<double> gaussian_kernel(double sigma, double truncation_sigmas = 8.0);

// Separable Gaussian with clamp-to-edge borders, accumulated in double. The default
// truncation (8σ) makes it the untruncated Gaussian to double precision.
ImageF gaussian_blur(const ImageF& image, double sigma, double truncation_sigmas = 8.0);

// Strength s in [0, 1] at pixel (x, y); `depth` (channel 0) may be null (depth term 1).
double blur_strength(int x, int y, int width, int height, const ImageF* depth,
                     const BlurParams& params);

// The `gaussian` method as specified: a stack of exact blurs at σmax, σmax/r, σmax/r², ...
// (r = 2^(1/levels_per_octave); at most 12 levels, none below 0.5 px) over the input, mixed
// per pixel by variance.
ImageF stacked_blur(const ImageF& image, const ImageF* depth, const BlurParams& params);

// The ideal variable blur: at each pixel the exact Gaussian of that pixel's own σ (gather).
ImageF exact_variable_blur(const ImageF& image, const ImageF* depth, const BlurParams& params);

// The largest σmax (pixels) the `gaussian` method blurs in one pass, and that pass's radius.
constexpr double kDirectBlurMaxSigma = 2.0;
// The one-pass radius for a varying σ up to `max_sigma`: 2·ceil(σmax), an even number >= 2.
int direct_blur_radius(double max_sigma);

// The one-pass variable blur: at each pixel the sampled Gaussian of its own σ truncated at
// `radius` taps per side and normalised over the (2·radius + 1)² taps kept.
ImageF truncated_variable_blur(const ImageF& image, const ImageF* depth, const BlurParams& params,
                               int radius);

// The `separable` kernel of the one-pass path at final quality: the truncated sampled Gaussian
// along rows, each pixel with its own σ, then along columns, each pixel with its own σ. Equal
// to truncated_variable_blur where σ is constant over a pixel's column of taps; elsewhere it
// mixes rows blurred with their own σ.
ImageF separable_variable_blur(const ImageF& image, const ImageF* depth, const BlurParams& params,
                               int radius);

// The one-pass path's `pinwheel` kernel: the per-pixel sampled Gaussian on the 5×5 taps less
// the 4 corners and (−2, 1), (1, 2), (2, −1), (−1, −2) (x right, y up), normalised over the
// 17 taps kept.
ImageF pinwheel_variable_blur(const ImageF& image, const ImageF* depth, const BlurParams& params);

// The `strided` method: 5×5 binomial kernel with strides 0.3σ and σ, bilinear clamp-to-edge
// reads, mixed by strength.
ImageF strided_blur(const ImageF& image, const ImageF* depth, const BlurParams& params);

}  // namespace aq::reference
