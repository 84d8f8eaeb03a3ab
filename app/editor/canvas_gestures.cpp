// Planning scripted mouse gestures on the canvas. See canvas_gestures.h.
#include "canvas_gestures.h"

#include <string>

namespace aq::editor {

namespace {

constexpr int kMoveSteps = 6;

const NodeLayout* find(const std::vector<NodeLayout>& layouts, const std::string& id) {
  for (const auto& layout : layouts) {
    if (layout.id == id) return &layout;
  }
  return nullptr;
}

Result<Vec2> spot(const std::vector<NodeLayout>& layouts, const std::string& text, bool input) {
  auto ref = PortRef::parse(text);
  if (!ref) return make_error("'" + text + "' is not \"node.port\"");
  // A node inside a collapsed group shows its ports on the group.
  if (find_node_layout(layouts, ref->node) == nullptr) {
    return make_error("node '" + ref->node + "' is not on the canvas");
  }
  if (const PortSpot* at = find_port_spot(layouts, ref->node, ref->port, input)) return at->at;
  return make_error("node '" + ref->node + "' shows no " + (input ? "input" : "output") + " '" +
                    ref->port + "'");
}

// Hover, press, move in steps, release, rest: what a hand does.
std::vector<MouseFrame> press_drag_release(Vec2 from, Vec2 to) {
  std::vector<MouseFrame> frames;
  frames.push_back({from.x, from.y, false, 0});
  frames.push_back({from.x, from.y, true, 0});
  for (int i = 1; i <= kMoveSteps; ++i) {
    float t = static_cast<float>(i) / kMoveSteps;
    frames.push_back({from.x + (to.x - from.x) * t, from.y + (to.y - from.y) * t, true, 0});
  }
  frames.push_back({to.x, to.y, false, 0});
  frames.push_back({to.x, to.y, false, 0});
  return frames;
}

// A hand faster than the UI: the press at `from` is seen by the first frame only once the mouse
// is already a third of the way to `to` (the window's callback reports where it happened).
std::vector<MouseFrame> quick_press_drag_release(Vec2 from, Vec2 to) {
  std::vector<MouseFrame> frames;
  frames.push_back({from.x, from.y, false, 0});
  for (int i = 2; i <= kMoveSteps; ++i) {
    float t = static_cast<float>(i) / kMoveSteps;
    frames.push_back({from.x + (to.x - from.x) * t, from.y + (to.y - from.y) * t, true, 0});
  }
  frames[1].press_after = 1.0f;
  frames[1].press_x = from.x;
  frames[1].press_y = from.y;
  frames.push_back({to.x, to.y, false, 0});
  frames.push_back({to.x, to.y, false, 0});
  return frames;
}

// Two clicks 0.15 s apart on a loaded machine: `slow_frames` UI frames pass between them, so
// the frames' own clock sees them far apart; the presses' times say otherwise.
std::vector<MouseFrame> double_click(Vec2 at, int slow_frames) {
  std::vector<MouseFrame> frames;
  frames.push_back({at.x, at.y, false, 0});
  MouseFrame press{at.x, at.y, true, 0};
  press.press_x = at.x;
  press.press_y = at.y;
  press.press_after = 1.0f;
  frames.push_back(press);
  frames.push_back({at.x, at.y, false, 0});
  for (int i = 0; i < slow_frames; ++i) frames.push_back({at.x, at.y, false, 0});
  press.press_after = 0.15f;
  frames.push_back(press);
  frames.push_back({at.x, at.y, false, 0});
  frames.push_back({at.x, at.y, false, 0});
  return frames;
}

}  // namespace

Result<std::vector<MouseFrame>> plan_gesture(const nlohmann::json& action,
                                             const std::vector<NodeLayout>& layouts, Vec2 origin,
                                             Vec2 size) {
  const std::string kind = action.value("do", std::string());
  if (kind == "drag_link") {
    auto from = spot(layouts, action.value("from", std::string()), false);
    if (!from) return from.error();
    auto to = spot(layouts, action.value("to", std::string()), true);
    if (!to) return to.error();
    return action.value("quick", false) ? quick_press_drag_release(*from, *to)
                                        : press_drag_release(*from, *to);
  }
  if (kind == "double_click_link") {
    // The middle of the link's curve into "to" (a symmetric cubic: halfway between its ends).
    auto to_ref = PortRef::parse(action.value("to", std::string()));
    if (!to_ref) return make_error("\"to\" must be \"node.input\"");
    auto to = spot(layouts, to_ref->str(), true);
    if (!to) return to.error();
    auto from = action.contains("from") ? spot(layouts, action.value("from", std::string()), false)
                                        : Result<Vec2>(make_error("needs \"from\": its source"));
    if (!from) return from.error();
    return double_click({(from->x + to->x) * 0.5f, (from->y + to->y) * 0.5f},
                        action.value("slow_frames", 30));
  }
  if (kind == "click_output") {
    auto at = spot(layouts, action.value("output", std::string()), false);
    if (!at) return at.error();
    return std::vector<MouseFrame>{
        {at->x, at->y, false, 0}, {at->x, at->y, true, 0}, {at->x, at->y, false, 0}};
  }
  if (kind == "drag_node") {
    const NodeLayout* layout = find(layouts, action.value("node", std::string()));
    if (layout == nullptr) return make_error("that node is not on the canvas");
    auto by = action.value("by", nlohmann::json::array());
    if (!by.is_array() || by.size() != 2 || !by[0].is_number() || !by[1].is_number()) {
      return make_error("\"by\" must be [dx, dy] in screen pixels");
    }
    // Grab the header away from the ports.
    Vec2 grab{(layout->header.min.x + layout->header.max.x) * 0.5f,
              (layout->header.min.y + layout->header.max.y) * 0.5f};
    return press_drag_release(grab, {grab.x + by[0].get<float>(), grab.y + by[1].get<float>()});
  }
  if (kind == "wheel") {
    float steps = action.value("steps", 1.0f);
    Vec2 centre{origin.x + size.x * 0.5f, origin.y + size.y * 0.5f};
    return std::vector<MouseFrame>{{centre.x, centre.y, false, 0},
                                   {centre.x, centre.y, false, steps},
                                   {centre.x, centre.y, false, 0}};
  }
  return make_error("not a mouse action: '" + kind + "'");
}

}  // namespace aq::editor
