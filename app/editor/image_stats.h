// The viewer's histogram: the minimum and maximum of the viewed image and how its values are
// spread between them (luminance for colour, the value for one channel), so a user can see
// clipping or an empty range at a glance, as Nuke's and Blender's scopes show. No GL.
#pragma once

#include <cstddef>
#include <vector>

namespace aq::editor {

struct ImageStats {
  float min = 0;  // over every finite value of the counted channels
  float max = 0;
  std::vector<float> bins;  // counts over [min, max], kBins of them
  size_t counted = 0;       // finite pixels
};

inline constexpr int kHistogramBins = 64;

// `pixels` holds `channels` floats a pixel (4: RGBA, the histogram of Rec. 709 luminance and
// min/max over r, g, b; 1: the value itself). Non-finite values are left out.
ImageStats image_stats(const std::vector<float>& pixels, int channels);

}  // namespace aq::editor
