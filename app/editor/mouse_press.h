// Left-button presses as they happened, not as the next UI frame sees them. A UI frame on a
// loaded machine can take 30-300 ms; by then a quick press-and-drag has left the port it began
// on (the canvas moved the node instead of starting a link), and ImGui, timing clicks by frame
// times, misses most double-clicks (a double-click on a link made a reroute dot about once in
// twelve tries). The window's GLFW callback records each press's place and time here, and the
// double-click is judged from those times. No GL.
#pragma once

#include <optional>

namespace aq::editor {

struct Press {
  float x = 0;
  float y = 0;
  bool double_click = false;  // the second press of a double-click
};

class PressTracker {
 public:
  static constexpr double kDoubleClickSeconds = 0.4;  // a little over ImGui's 0.3 s
  static constexpr float kDoubleClickPixels = 6.0f;

  // A press at (x, y) at `time` (seconds); tells whether it completes a double-click.
  Press press(double time, float x, float y);

 private:
  std::optional<double> last_time_;
  float last_x_ = 0;
  float last_y_ = 0;
};

}  // namespace aq::editor
