// Presses and double-clicks from event times. See mouse_press.h.
#include "mouse_press.h"

#include <cmath>

namespace aq::editor {

Press PressTracker::press(double time, float x, float y) {
  Press press{x, y, false};
  if (last_time_ && time - *last_time_ <= kDoubleClickSeconds &&
      std::hypot(x - last_x_, y - last_y_) <= kDoubleClickPixels) {
    press.double_click = true;
    last_time_.reset();  // a third press starts a new pair
  } else {
    last_time_ = time;
  }
  last_x_ = x;
  last_y_ = y;
  return press;
}

}  // namespace aq::editor
