// UI frame times, as the editor measures itself: the status bar shows the recent average and
// the scripted mode prints a summary at exit, split by whether an evaluation was in flight
// while the frame was drawn (the UI must stay fluid while the graph renders).
#pragma once

#include <cstddef>
#include <deque>
#include <string>
#include <vector>

namespace aq::editor {

class FrameStats {
 public:
  // One UI frame: the time since the previous one began, and whether the evaluation worker
  // was busy during it.
  void add(double frame_ms, bool evaluating);
  // Mean of the last few frames (ms), 0 before any.
  double recent_ms() const;
  size_t frames() const { return all_.size(); }
  size_t frames_while_evaluating() const { return evaluating_.size(); }
  // "UI frames: 212 (148 while evaluating); frame time median 9.8 ms, 95% 21.0 ms (102 fps);
  //  while evaluating median 11.2 ms, 95% 24.9 ms (89 fps)"
  std::string summary() const;

 private:
  static constexpr size_t kRecent = 30;
  std::vector<double> all_;
  std::vector<double> evaluating_;
  std::deque<double> recent_;
};

// The q-quantile (0..1) of `values` (nearest rank); 0 when empty.
double quantile(std::vector<double> values, double q);

}  // namespace aq::editor
