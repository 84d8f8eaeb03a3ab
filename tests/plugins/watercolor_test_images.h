// Small helpers shared by the watercolor node tests (erode, dilate, morphology, wobble, edge,
// pigment): images whose values survive half precision unchanged, and per-pixel predicates.
#pragma once

#include <aquarelle/core/image.h>

#include <cmath>
#include <string>

namespace aq::test::watercolor {

// Rounds every value to a multiple of 1/1024: such values in [0, 1] are exact in half
// precision, so a node that only selects or copies values must reproduce them bit for bit in
// both precisions.
inline ImageF quantized(ImageF image) {
  for (float& v : image.pixels) v = std::round(v * 1024.0f) / 1024.0f;
  return image;
}

inline double luminance(const ImageF& image, int x, int y) {
  return 0.2126 * image.at(x, y, 0) + 0.7152 * image.at(x, y, 1) + 0.0722 * image.at(x, y, 2);
}

// Both precisions every parameterised test runs in, with the tolerance on a value that should
// be reproduced exactly up to the storage format (RGBA32F or RGBA16F).
struct PrecisionCase {
  std::string precision;
  double storage_tolerance;  // absolute, for values in [0, 1]
};
inline const PrecisionCase kFloat{"float", 1e-6};
inline const PrecisionCase kHalf{"half", 1.0 / 2048.0};  // half ulp at 1.0 is 2^-10

}  // namespace aq::test::watercolor
