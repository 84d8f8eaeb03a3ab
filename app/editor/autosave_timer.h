// When the editor writes its autosave side file: shortly after each completed edit (once the
// document has not changed for `debounce` seconds and no slider or node drag is under way), so
// a crash or a kill loses at most about a second of work; and every `period` seconds during a
// long gesture. No GL, no files: the caller writes (Document::autosave) when due() says so.
#pragma once

#include <cstdint>

namespace aq::editor {

class AutosaveTimer {
 public:
  static constexpr double kDebounceSeconds = 0.5;  // leaves slack for slow frames under 1 s
  static constexpr double kPeriodSeconds = 30.0;

  explicit AutosaveTimer(double debounce = kDebounceSeconds, double period = kPeriodSeconds)
      : debounce_(debounce), period_(period) {}

  // Called once per UI frame with the clock, the document's revision and whether a gesture is
  // open; true when the autosave should be written now.
  bool due(double now, uint64_t revision, bool in_gesture);
  // The autosave of `revision` was written (or there was nothing to write) at `now`.
  void written(double now, uint64_t revision);

 private:
  double debounce_;
  double period_;
  uint64_t seen_revision_ = 0;
  double changed_at_ = 0;
  bool started_ = false;
  uint64_t written_revision_ = 0;
  double written_at_ = 0;
};

}  // namespace aq::editor
