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
// Also: "delete" / "duplicate" / "select" {"nodes": [...]}, "set_output" {"output"},
// "frame" {"frame"}, "fit". An action whose outcome differs from "expect" ("ok" by default, or
// "refused") stops the script with a message naming the action.
#pragma once

#include "editor_state.h"

#include <aquarelle/core/result.h>

#include <nlohmann/json.hpp>

#include <functional>
#include <string>

namespace aq::editor {

struct ScriptHooks {
  std::function<void()> fit;  // View > Fit, which needs the canvas
};

// Reads a script file (an object with "actions", or a bare array).
Result<nlohmann::json> read_script(const std::string& path);
// Runs every action in order; returns the first unexpected outcome as an error.
Status run_script(EditorState& state, const nlohmann::json& actions, const ScriptHooks& hooks = {});

}  // namespace aq::editor
