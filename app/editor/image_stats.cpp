// The viewer's histogram and range. See image_stats.h.
#include "image_stats.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace aq::editor {

ImageStats image_stats(const std::vector<float>& pixels, int channels) {
  ImageStats stats;
  stats.bins.assign(kHistogramBins, 0.0f);
  if (channels < 1) return stats;
  const size_t count = pixels.size() / static_cast<size_t>(channels);
  const int coloured = channels >= 3 ? 3 : 1;
  std::vector<float> values;  // what the histogram counts, one a pixel
  values.reserve(count);
  float lo = std::numeric_limits<float>::infinity();
  float hi = -lo;
  for (size_t i = 0; i < count; ++i) {
    const float* p = &pixels[i * channels];
    bool finite = true;
    for (int c = 0; c < coloured; ++c) finite = finite && std::isfinite(p[c]);
    if (!finite) continue;
    for (int c = 0; c < coloured; ++c) {
      lo = std::min(lo, p[c]);
      hi = std::max(hi, p[c]);
    }
    values.push_back(coloured == 3 ? 0.2126f * p[0] + 0.7152f * p[1] + 0.0722f * p[2] : p[0]);
  }
  stats.counted = values.size();
  if (values.empty()) return stats;
  stats.min = lo;
  stats.max = hi;
  const float span = hi > lo ? hi - lo : 1.0f;
  for (float v : values) {
    const int bin =
        std::clamp(static_cast<int>((v - lo) / span * kHistogramBins), 0, kHistogramBins - 1);
    stats.bins[bin] += 1.0f;
  }
  return stats;
}

}  // namespace aq::editor
