// Summaries of repeated timings for `aquarelle bench`: the median as the figure to quote and
// the spread (min, quartiles, max) so a reader sees how noisy the figure is.
#pragma once

#include <vector>

namespace aq::app {

struct Spread {
  double median = 0;
  double min = 0;
  double q1 = 0;  // 25th percentile
  double q3 = 0;  // 75th percentile
  double max = 0;
  int count = 0;
};

// Linear-interpolated quantiles of `samples`; all zero when empty.
Spread summarize(std::vector<double> samples);

}  // namespace aq::app
