// The frame rate playback actually reaches: how many new frames of the graph reach the screen
// per second while playing, over the last kWindow of them. Shown beside the graph's own fps
// setting, which the editor may not keep up with (each frame is evaluated before the next is
// shown). Not the UI's redraw rate: an idle UI redraws only on demand. No GL.
#pragma once

#include <cstddef>
#include <deque>

namespace aq::editor {

class PlaybackRate {
 public:
  static constexpr size_t kWindow = 24;
  // Called every UI frame while playing, with the clock (s) and the graph frame on screen.
  void shown(double now, int frame);
  // Forgets the last playback (playback starts again).
  void reset();
  // Frames per second reached; 0 until two frames were shown.
  double fps() const;

 private:
  int last_frame_ = -1;
  std::deque<double> times_;
};

}  // namespace aq::editor
