// CPU reference of the `tint` node in double precision (plugins/tint/README.md):
// out.rgb = in.rgb + (tint - in.rgb)·amount, out.a = in.a.
#pragma once

#include <aquarelle/core/image.h>

#include <array>

namespace aq::reference {

struct TintParams {
  double amount = 0.75;
  std::array<double, 3> tint{0.0, 0.07, 0.1};
};

ImageF tint(const ImageF& image, const TintParams& params = {});

}  // namespace aq::reference
