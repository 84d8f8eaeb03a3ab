// UI frame-time bookkeeping. See frame_stats.h.
#include "frame_stats.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numeric>

namespace aq::editor {

double quantile(std::vector<double> values, double q) {
  if (values.empty()) return 0;
  std::sort(values.begin(), values.end());
  const double rank = std::clamp(q, 0.0, 1.0) * static_cast<double>(values.size() - 1);
  return values[static_cast<size_t>(std::lround(rank))];
}

void FrameStats::add(double frame_ms, bool evaluating) {
  all_.push_back(frame_ms);
  if (evaluating) evaluating_.push_back(frame_ms);
  recent_.push_back(frame_ms);
  if (recent_.size() > kRecent) recent_.pop_front();
}

double FrameStats::recent_ms() const {
  if (recent_.empty()) return 0;
  return std::accumulate(recent_.begin(), recent_.end(), 0.0) / static_cast<double>(recent_.size());
}

std::string FrameStats::summary() const {
  auto part = [](const std::vector<double>& values) {
    const double median = quantile(values, 0.5);
    char text[128];
    std::snprintf(text, sizeof text, "median %.1f ms, 95%% %.1f ms (%.0f fps)", median,
                  quantile(values, 0.95), median > 0 ? 1000.0 / median : 0.0);
    return std::string(text);
  };
  std::string out = "UI frames: " + std::to_string(all_.size()) + " (" +
                    std::to_string(evaluating_.size()) + " while evaluating); frame time " +
                    part(all_);
  if (!evaluating_.empty()) out += "; while evaluating " + part(evaluating_);
  return out;
}

}  // namespace aq::editor
