// Where named widgets (menus, menu items, the splitter, the viewer's checkboxes, parameter
// sliders) were drawn, so scripted mouse actions can aim at them as a user's hand does: the
// script names the widget, the window plays a real press, move and release over it. The canvas
// has its own geometry (canvas_gestures.h); this covers the ImGui widgets around it.
#pragma once

#include "script.h"

#include <aquarelle/core/result.h>

#include <nlohmann/json.hpp>

#include <optional>
#include <string>
#include <vector>

namespace aq::editor {

struct ItemRect {
  float x0 = 0, y0 = 0, x1 = 0, y1 = 0;
};

// Records the last ImGui item drawn under `name` (call right after the widget).
void note_item(const std::string& name);
// Starts a UI frame: what was noted in the last frame becomes what find_item answers.
void begin_item_frame();
// Where `name` was drawn in the last complete frame; nullopt when it was not drawn.
std::optional<ItemRect> find_item(const std::string& name);

// The mouse frames of a widget action, aimed at widgets by name (resolved when played):
//   {"do": "click", "items": ["File", "Open Recent", "/abs/graph.json"]}  clicks each in turn
//   {"do": "hover", "item": "param:sigma", "frames": 10}
//   {"do": "drag", "item": "##split", "by": [200, 0], "steps": 12, "hold": 4}
// nullopt for an action of another kind.
std::optional<Result<std::vector<MouseFrame>>> plan_item_gesture(const nlohmann::json& action);

}  // namespace aq::editor
