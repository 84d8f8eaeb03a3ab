// The scripted mode: a JSON list of editor actions run through editor_actions.h, the same
// functions the mouse and menus call, so tests drive the real editor.
//
//   {"actions": [
//     {"do": "add_node", "type": "blur", "id": "soft", "at": [400, 80]},
//     {"do": "link", "from": "tint.image", "to": "soft.image"},
//     {"do": "link", "from": "scene.scene", "to": "soft.image", "expect": "refused"},
//     {"do": "set_param", "node": "soft", "param": "sigma", "value": 4.0},
//     {"do": "move", "node": "soft", "to": [420, 90]},
//     {"do": "select_output", "output": "gbuf.depth"},
//     {"do": "unlink", "to": "soft.image"},
//     {"do": "undo"}, {"do": "redo"},
//     {"do": "save", "path": "out.json"}          // path optional: the graph's own file
//   ]}
//
// Mouse actions, played as real input on the canvas over several frames:
//   {"do": "drag_link", "from": "tint.image", "to": "soft.image"}   output port to input port
//   {"do": "drag_node", "node": "soft", "by": [120, 40]}            screen pixels
//   {"do": "click_output", "output": "gbuf.depth"}                  views that output
//   {"do": "wheel", "steps": 2}                                     zoom at the canvas centre
//   {"do": "click", "items": ["File", "Open Recent", "/abs/g.json"]} widgets by name, in turn
//   {"do": "drag", "item": "##split", "by": [200, 0]}               press, move, release
//   {"do": "hover", "item": "param:sigma", "frames": 10}            (item_rects.h for names)
//   {"do": "drag_link", ..., "quick": true}   the press seen by the UI only after the mouse left
//                                            the port (a hand faster than a frame)
//   {"do": "double_click_link", "from": "light.image", "to": "tint.image", "slow_frames": 30}
//                                            two clicks 0.15 s apart at the link's middle, with
//                                            that many UI frames between them
//
// Also: "delete" / "duplicate" / "select" {"nodes": [...]}, "set_output" {"output"},
// "frame" {"frame"}, "fit" {"whole": true for every node however small}, "add_menu" {"filter"}
// (opens the add-node menu, for screenshots), "key" {"chord": "ctrl+d"} (a key press as if released
// before the next frame: the canvas keys act with the mouse over the canvas), "copy", "paste"
// {"at"}, "rename" {"node", "to"}, "bypass" {"nodes"}, "auto_layout", "backdrop" {"nodes",
// "label"}, "insert" {"type", "after": "node.port" | "on": "node.input", "at"}, "dot" {"to":
// "node.input", "at"}, "group" {"nodes" (or the selection)}, "ungroup" {"nodes"}, "collapse" /
// "expand" {"group": name}, "compare" {"output": "node.port" | null} (B of the A/B wipe), "wait"
// {"frames": N} (lets N UI frames pass), "play" {"frames": N} (plays until N frames later is on
// screen, at the editor's own pace). An action whose outcome differs from "expect" ("ok" by
// default, or "refused") stops the script with a message naming the action.
#pragma once

#include "editor_state.h"

#include <aquarelle/core/result.h>

#include <nlohmann/json.hpp>

#include <functional>
#include <string>
#include <vector>

namespace aq::editor {

// A mouse action becomes these frames of synthetic input, fed to ImGui in place of the real
// mouse, so the canvas's own handlers do the work.
struct MouseFrame {
  float x = 0;
  float y = 0;
  bool left_down = false;
  float wheel = 0;
  // A left press as the window's callback reports it, when this frame carries one: where it
  // happened and how long after the previous such press (seconds; < 0: none).
  float press_after = -1;
  float press_x = 0;
  float press_y = 0;
  // Aimed at a named widget (item_rects.h) rather than the canvas: x, y are then offsets from
  // the widget's centre as drawn in the last frame, or, with from_press, from where this
  // gesture pressed.
  std::string item{};  // (braced: canvas gestures list only the first fields)
  bool from_press = false;
};

struct ScriptHooks {
  std::function<void(bool whole)> fit;  // View > Fit (whole: every node, however small)
  std::function<void(const std::string&)> add_menu;  // opens the add-node menu (screenshots)
  // The frame of the image on screen once the viewer is settled, -1 while it evaluates.
  std::function<int()> shown_frame;
  // The frame rate the last playback reached (frames shown per second).
  std::function<double()> playback_fps;
  // Presses a key chord ("ctrl+shift+s") as if pressed and released between two frames.
  std::function<Status(const std::string&)> key;
  // The system clipboard (the window's); without them a stand-in inside the script runner.
  std::function<void(const std::string&)> set_clipboard;
  std::function<std::string()> get_clipboard;
  // View options: {"backdrop": bool} shows the viewer's image behind the nodes,
  // {"hold_a": true} keeps the viewer's picture as A of the wipe compare.
  std::function<Status(const nlohmann::json&)> view;
  // Files dropped on the window: calls the drop callback GLFW has registered for the window.
  std::function<Status(const std::vector<std::string>&)> drop;
  // Checks what the window shows ({"split", "histogram", "tooltips", "document"}); the status
  // line reports what was found.
  std::function<Status(const nlohmann::json&)> expect_view;
  // Turns a mouse action into input frames from the canvas's current layout; an error when a
  // node or port it names is not on the canvas.
  std::function<Result<std::vector<MouseFrame>>(const nlohmann::json&)> gesture;
};

// Reads a script file (an object with "actions", or a bare array).
Result<nlohmann::json> read_script(const std::string& path);

// Runs a script across frames: call step() once per frame after the UI was drawn. Ordinary
// actions run at once; a mouse action hands its frames out through `gesture_frames` and the
// runner judges its outcome (refused or not) once they were played.
class ScriptRunner {
 public:
  explicit ScriptRunner(nlohmann::json actions) : actions_(std::move(actions)) {}
  // Returns an error at the first unexpected outcome; finished() tells when all ran.
  Status step(EditorState& state, const ScriptHooks& hooks,
              std::vector<MouseFrame>* gesture_frames);
  bool finished() const {
    return next_ >= actions_.size() && !waiting_ && play_until_ < 0 && wait_frames_ == 0;
  }

 private:
  Status judge(EditorState& state, const Status& outcome);

  nlohmann::json actions_;
  size_t next_ = 0;
  bool waiting_ = false;    // a gesture is being played
  int refused_before_ = 0;  // state.refused_count when the gesture began
  bool laid_out_ = false;   // a frame was drawn since the last ordinary action
  int play_until_ = -1;     // a "play" action waits for this frame to be shown
  int wait_frames_ = 0;     // a "wait" action lets this many UI frames pass
};

// Runs every action in order without mouse actions (tests, or a script with no window).
Status run_script(EditorState& state, const nlohmann::json& actions, const ScriptHooks& hooks = {});

}  // namespace aq::editor
