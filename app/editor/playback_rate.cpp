// Playback's reached frame rate. See playback_rate.h.
#include "playback_rate.h"

namespace aq::editor {

void PlaybackRate::shown(double now, int frame) {
  if (frame == last_frame_) return;
  last_frame_ = frame;
  times_.push_back(now);
  while (times_.size() > kWindow) times_.pop_front();
}

void PlaybackRate::reset() {
  last_frame_ = -1;
  times_.clear();
}

double PlaybackRate::fps() const {
  if (times_.size() < 2) return 0.0;
  const double span = times_.back() - times_.front();
  return span > 0 ? static_cast<double>(times_.size() - 1) / span : 0.0;
}

}  // namespace aq::editor
