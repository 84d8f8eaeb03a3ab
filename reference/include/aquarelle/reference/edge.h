// CPU reference of the `edge` node (plugins/edge/README.md) in double precision: the 3×3
// Laplacian (−8 centre) or Sobel response per channel on the source with clamp-to-edge borders,
// the largest channel response through smoothstep, and the HSV value scaled towards `factor`
// (done through an actual RGB → HSV → RGB round trip, so it also checks that the shader's
// direct RGB scaling is the same thing).
#pragma once

#include <aquarelle/core/image.h>

namespace aq::reference {

enum class EdgeKernel { kLaplacian, kSobel };

struct EdgeParams {
  EdgeKernel kernel = EdgeKernel::kLaplacian;
  double factor = 0.7;
  double threshold = 0.1;
  double softness = 0.2;
};

// Largest absolute channel response at pixel (x, y) of `source`.
double edge_response(const ImageF& source, int x, int y, EdgeKernel kernel);

// `source` may be null (edges of `image` itself) or any size (its pixel under each output
// pixel's centre is used).
ImageF edge_darkening(const ImageF& image, const ImageF* source, const EdgeParams& params);

}  // namespace aq::reference
