// Quantile summaries for `aquarelle bench` (see bench_stats.h).
#include "bench_stats.h"

#include <algorithm>
#include <cmath>

namespace aq::app {

namespace {

// Quantile q in [0, 1] of sorted samples, interpolating between neighbours (type 7).
double quantile(const std::vector<double>& sorted, double q) {
  const double position = q * static_cast<double>(sorted.size() - 1);
  const size_t below = static_cast<size_t>(std::floor(position));
  const size_t above = std::min(below + 1, sorted.size() - 1);
  const double t = position - static_cast<double>(below);
  return sorted[below] + (sorted[above] - sorted[below]) * t;
}

}  // namespace

Spread summarize(std::vector<double> samples) {
  Spread spread;
  if (samples.empty()) return spread;
  std::sort(samples.begin(), samples.end());
  spread.count = static_cast<int>(samples.size());
  spread.min = samples.front();
  spread.max = samples.back();
  spread.median = quantile(samples, 0.5);
  spread.q1 = quantile(samples, 0.25);
  spread.q3 = quantile(samples, 0.75);
  return spread;
}

}  // namespace aq::app
