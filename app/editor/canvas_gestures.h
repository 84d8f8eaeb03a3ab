// Scripted mouse gestures: a mouse action of the scripted mode ("drag_link", "drag_node",
// "click_output", "wheel") planned as frames of synthetic input aimed at the canvas as last
// drawn, so the canvas's own mouse handlers do the editing.
#pragma once

#include "canvas_view.h"
#include "script.h"

#include <aquarelle/core/result.h>

#include <nlohmann/json.hpp>

#include <vector>

namespace aq::editor {

Result<std::vector<MouseFrame>> plan_gesture(const nlohmann::json& action,
                                             const std::vector<NodeLayout>& layouts, Vec2 origin,
                                             Vec2 size);

}  // namespace aq::editor
