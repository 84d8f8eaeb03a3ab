// Named widget rectangles and the scripted gestures aimed at them. See item_rects.h.
#include "item_rects.h"

#include <imgui.h>

#include <algorithm>
#include <map>
#include <stdexcept>

namespace aq::editor {

namespace {

std::map<std::string, ItemRect>& drawing() {
  static std::map<std::string, ItemRect> rects;
  return rects;
}

std::map<std::string, ItemRect>& drawn() {
  static std::map<std::string, ItemRect> rects;
  return rects;
}

MouseFrame at_item(const std::string& item, float dx, float dy, bool down) {
  MouseFrame frame;
  frame.item = item;
  frame.x = dx;
  frame.y = dy;
  frame.left_down = down;
  return frame;
}

std::vector<std::string> item_names(const nlohmann::json& action) {
  std::vector<std::string> names;
  if (action.contains("item") && action["item"].is_string()) {
    names.push_back(action["item"].get<std::string>());
  }
  if (action.contains("items") && action["items"].is_array()) {
    for (const auto& name : action["items"]) {
      if (!name.is_string()) throw std::invalid_argument("\"items\" must hold widget names");
      names.push_back(name.get<std::string>());
    }
  }
  if (names.empty()) throw std::invalid_argument("needs \"item\" or \"items\": widget names");
  return names;
}

}  // namespace

void note_item(const std::string& name) {
  const ImVec2 min = ImGui::GetItemRectMin();
  const ImVec2 max = ImGui::GetItemRectMax();
  drawing()[name] = {min.x, min.y, max.x, max.y};
}

void begin_item_frame() {
  drawn() = std::move(drawing());
  drawing().clear();
}

std::optional<ItemRect> find_item(const std::string& name) {
  auto it = drawn().find(name);
  if (it == drawn().end()) return std::nullopt;
  return it->second;
}

std::optional<Result<std::vector<MouseFrame>>> plan_item_gesture(const nlohmann::json& action) {
  const std::string kind = action.value("do", std::string());
  if (kind != "click" && kind != "hover" && kind != "drag") return std::nullopt;
  const std::vector<std::string> names = item_names(action);
  std::vector<MouseFrame> frames;
  if (kind == "click") {
    for (const std::string& name : names) {
      // Hover first (a sub-menu opens under the mouse), then press and release on it.
      for (int i = 0; i < 3; ++i) frames.push_back(at_item(name, 0, 0, false));
      frames.push_back(at_item(name, 0, 0, true));
      for (int i = 0; i < 3; ++i) frames.push_back(at_item(name, 0, 0, false));
    }
    return frames;
  }
  const std::string& name = names.front();
  if (kind == "hover") {
    const int count = std::max(action.value("frames", 5), 1);
    for (int i = 0; i < count; ++i) frames.push_back(at_item(name, 0, 0, false));
    return frames;
  }
  auto by = action.find("by");
  if (by == action.end() || !by->is_array() || by->size() != 2 || !(*by)[0].is_number() ||
      !(*by)[1].is_number()) {
    throw std::invalid_argument("\"by\" must be [dx, dy] in screen pixels");
  }
  const float dx = (*by)[0].get<float>();
  const float dy = (*by)[1].get<float>();
  const int steps = std::max(action.value("steps", 12), 1);
  const int hold = std::max(action.value("hold", 3), 0);
  frames.push_back(at_item(name, 0, 0, false));
  frames.push_back(at_item(name, 0, 0, true));
  // The moves are relative to where the press happened: the widget may move under the mouse
  // (the splitter does), the hand does not.
  for (int i = 1; i <= steps; ++i) {
    MouseFrame move = at_item(name, dx * i / steps, dy * i / steps, true);
    move.from_press = true;
    frames.push_back(move);
  }
  for (int i = 0; i < hold; ++i) {
    MouseFrame still = at_item(name, dx, dy, true);
    still.from_press = true;
    frames.push_back(still);
  }
  MouseFrame release = at_item(name, dx, dy, false);
  release.from_press = true;
  frames.push_back(release);
  return frames;
}

}  // namespace aq::editor
