// The node canvas: drawing with ImGui draw lists and the mouse and key handling. See canvas.h.
#include "canvas.h"

#include "editor_actions.h"

#include <imgui.h>
#include <imgui_stdlib.h>
#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <functional>
#include <set>

namespace aq::editor {

namespace {

ImVec2 im(Vec2 v) {
  return ImVec2(v.x, v.y);
}
Vec2 vec(ImVec2 v) {
  return Vec2{v.x, v.y};
}

ImU32 port_colour(aq_port_type type) {
  return type == AQ_PORT_SCENE ? IM_COL32(250, 170, 80, 255) : IM_COL32(110, 175, 255, 255);
}

// A stable, muted colour per category so nodes of a kind read alike.
ImU32 category_colour(const std::string& category) {
  uint32_t h = static_cast<uint32_t>(std::hash<std::string>{}(category));
  float hue = (h % 360) / 360.0f;
  float r, g, b;
  ImGui::ColorConvertHSVtoRGB(hue, 0.45f, 0.55f, r, g, b);
  return ImGui::ColorConvertFloat4ToU32(ImVec4(r, g, b, 1.0f));
}

std::string lower(std::string text) {
  for (char& c : text) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return text;
}

void draw_link(ImDrawList* draw, Vec2 from, Vec2 to, ImU32 colour, float zoom) {
  float dx = std::max(std::fabs(to.x - from.x) * 0.5f, 30.0f * zoom);
  draw->AddBezierCubic(im(from), ImVec2(from.x + dx, from.y), ImVec2(to.x - dx, to.y), im(to),
                       colour, std::max(1.5f, 2.5f * zoom));
}

void text_at(ImDrawList* draw, Vec2 at, float zoom, ImU32 colour, const std::string& text) {
  draw->AddText(ImGui::GetFont(), ImGui::GetFontSize() * zoom, im(at), colour, text.c_str());
}

const NodeLayout* find_layout(const std::vector<NodeLayout>& layouts, const std::string& id) {
  for (const auto& layout : layouts) {
    if (layout.id == id) return &layout;
  }
  return nullptr;
}

const PortSpot* find_spot(const std::vector<PortSpot>& spots, const std::string& port) {
  for (const auto& spot : spots) {
    if (spot.port == port) return &spot;
  }
  return nullptr;
}

}  // namespace

void Canvas::draw(EditorState& state, const NodeFeedback& feedback) {
  const Graph& graph = state.doc.graph();
  const Registry& registry = state.doc.registry();
  ImVec2 available = ImGui::GetContentRegionAvail();
  size_ = {std::max(available.x, 50.0f), std::max(available.y, 50.0f)};
  origin_ = vec(ImGui::GetCursorScreenPos());
  CanvasView& view = state.canvas;
  if (fit_requested_) {
    view.fit(graph_bounds(graph, registry), size_);
    fit_requested_ = false;
  }

  ImDrawList* draw = ImGui::GetWindowDrawList();
  ImVec2 lo = im(origin_);
  ImVec2 hi(origin_.x + size_.x, origin_.y + size_.y);
  draw->PushClipRect(lo, hi, true);
  draw->AddRectFilled(lo, hi, IM_COL32(32, 34, 38, 255));
  // Grid every 40 canvas units, so zoom is visible even on an empty graph.
  float step = 40.0f * view.zoom;
  if (step > 6.0f) {
    for (float x = std::fmod(view.pan.x, step); x < size_.x; x += step) {
      draw->AddLine(ImVec2(lo.x + x, lo.y), ImVec2(lo.x + x, hi.y), IM_COL32(48, 50, 56, 255));
    }
    for (float y = std::fmod(view.pan.y, step); y < size_.y; y += step) {
      draw->AddLine(ImVec2(lo.x, lo.y + y), ImVec2(hi.x, lo.y + y), IM_COL32(48, 50, 56, 255));
    }
  }

  // The invisible button owns the canvas's mouse input; nodes are drawn over it.
  ImGui::InvisibleButton("##canvas", im(size_),
                         ImGuiButtonFlags_MouseButtonLeft | ImGuiButtonFlags_MouseButtonRight |
                             ImGuiButtonFlags_MouseButtonMiddle);
  std::vector<NodeLayout> layouts = layout_graph(graph, registry, view, origin_);
  // Selected nodes are drawn last, so on top, and are the first hit where nodes overlap.
  std::stable_partition(layouts.begin(), layouts.end(),
                        [&](const NodeLayout& l) { return !state.selection.count(l.id); });

  // Links.
  for (const auto& [id, node] : graph.nodes) {
    const NodeLayout* target = find_layout(layouts, id);
    for (const auto& [port, source] : node.inputs) {
      const NodeLayout* from = find_layout(layouts, source.node);
      if (target == nullptr || from == nullptr) continue;
      const PortSpot* out = find_spot(from->outputs, source.port);
      const PortSpot* in = find_spot(target->inputs, port);
      if (out == nullptr || in == nullptr) continue;
      draw_link(draw, out->at, in->at, port_colour(out->type), view.zoom);
    }
  }

  // Nodes.
  const auto shown = state.shown_output();
  const float z = view.zoom;
  const float rounding = 5.0f * z;
  for (const auto& layout : layouts) {
    const Node& node = graph.nodes.at(layout.id);
    const NodeType* type = registry.find(node.type);
    auto problems = state.doc.problems_of(layout.id);
    bool failed = !problems.empty() || feedback.error_node == layout.id || type == nullptr;
    bool selected = state.selection.count(layout.id) > 0;
    draw->AddRectFilled(im(layout.rect.min), im(layout.rect.max), IM_COL32(58, 60, 66, 240),
                        rounding);
    draw->AddRectFilled(im(layout.header.min), im(layout.header.max),
                        type ? category_colour(type->category) : IM_COL32(120, 40, 40, 255),
                        rounding, ImDrawFlags_RoundCornersTop);
    ImU32 border = failed     ? IM_COL32(255, 80, 70, 255)
                   : selected ? IM_COL32(255, 220, 120, 255)
                              : IM_COL32(20, 20, 22, 255);
    draw->AddRect(im(layout.rect.min), im(layout.rect.max), border, rounding, 0,
                  failed || selected ? 2.5f : 1.0f);
    std::string title = layout.id == node.type ? layout.id : layout.id + " (" + node.type + ")";
    if (failed) title = "! " + title;
    text_at(draw, {layout.header.min.x + 6 * z, layout.header.min.y + 4 * z}, z,
            IM_COL32(245, 245, 245, 255), title);
    for (const auto& spot : layout.inputs) {
      bool linked = node.inputs.count(spot.port) > 0;
      draw->AddCircleFilled(im(spot.at), NodeMetrics::kPortRadius * z,
                            linked ? port_colour(spot.type) : IM_COL32(70, 70, 76, 255));
      draw->AddCircle(im(spot.at), NodeMetrics::kPortRadius * z, port_colour(spot.type), 0, 1.5f);
      // A port holding several links (AQ_PORT_MULTI) says how many.
      const size_t links = node.inputs.count(spot.port);
      text_at(draw, {spot.at.x + 9 * z, spot.at.y - 7 * z}, z, IM_COL32(210, 210, 215, 255),
              links > 1 ? spot.port + " (" + std::to_string(links) + ")" : spot.port);
    }
    for (const auto& spot : layout.outputs) {
      draw->AddCircleFilled(im(spot.at), NodeMetrics::kPortRadius * z, port_colour(spot.type));
      if (shown && shown->node == layout.id && shown->port == spot.port) {
        draw->AddCircle(im(spot.at), (NodeMetrics::kPortRadius + 4) * z,
                        IM_COL32(255, 255, 255, 255), 0, 2.0f);
      }
      ImVec2 text_size =
          ImGui::GetFont()->CalcTextSizeA(ImGui::GetFontSize() * z, FLT_MAX, 0, spot.port.c_str());
      text_at(draw, {spot.at.x - 9 * z - text_size.x, spot.at.y - 7 * z}, z,
              IM_COL32(210, 210, 215, 255), spot.port);
    }
    // Footer: GPU time of the last evaluation.
    std::string footer;
    auto timing = feedback.timings.find(layout.id);
    if (timing != feedback.timings.end()) {
      char text[64];
      std::snprintf(text, sizeof text, "gpu %.2f ms%s", timing->second.gpu_ms,
                    timing->second.cached ? "  (cached)" : "");
      footer = text;
    } else {
      footer = "not evaluated";
    }
    text_at(draw, {layout.rect.min.x + 6 * z, layout.rect.max.y - NodeMetrics::kFooter * z}, z,
            IM_COL32(150, 200, 150, 255), footer);
    // The reason a node is marked, on hover.
    if (failed && ImGui::IsWindowHovered() && layout.rect.contains(vec(ImGui::GetMousePos()))) {
      std::string why;
      if (type == nullptr) why += "type '" + node.type + "' is not installed\n";
      for (const auto& problem : problems) why += problem.message + "\n";
      if (feedback.error_node == layout.id) why += feedback.error;
      ImGui::SetTooltip("%s", why.c_str());
    }
  }

  handle_mouse(state, layouts, origin_);
  layouts_ = std::move(layouts);
  draw->PopClipRect();
  if (ImGui::IsWindowFocused(ImGuiFocusedFlags_ChildWindows) && !ImGui::GetIO().WantTextInput) {
    handle_keys(state);
  }
  draw_add_menu(state);
  draw_node_menu(state);
}

void Canvas::handle_mouse(EditorState& state, const std::vector<NodeLayout>& layouts, Vec2 origin) {
  ImGuiIO& io = ImGui::GetIO();
  ImDrawList* draw = ImGui::GetWindowDrawList();
  CanvasView& view = state.canvas;
  const Vec2 mouse = vec(io.MousePos);
  const bool hovered = ImGui::IsItemHovered();
  const float reach = std::max(NodeMetrics::kPortRadius * view.zoom + 4.0f, 8.0f);

  if (hovered && io.MouseWheel != 0.0f) view.zoom_at(origin, mouse, std::pow(1.15f, io.MouseWheel));

  // Pan with the middle or right button.
  for (ImGuiMouseButton button : {ImGuiMouseButton_Middle, ImGuiMouseButton_Right}) {
    if (ImGui::IsItemActive() && ImGui::IsMouseDragging(button, 3.0f)) {
      view.pan.x += io.MouseDelta.x;
      view.pan.y += io.MouseDelta.y;
      if (button == ImGuiMouseButton_Right) drag_ = Drag::kPan;
    }
  }
  if (hovered && ImGui::IsMouseReleased(ImGuiMouseButton_Right)) {
    if (drag_ != Drag::kPan) {
      menu_node_ = node_at(layouts, mouse);
      if (menu_node_) {
        if (!state.selection.count(*menu_node_)) actions::select(state, {*menu_node_});
        ImGui::OpenPopup("node_menu");
      } else {
        Vec2 at = view.to_canvas(origin, mouse);
        add_at_ = {at.x, at.y};
        add_filter_.clear();
        ImGui::OpenPopup("add_node");
      }
    }
    drag_ = Drag::kNone;
  }

  // Left button: press starts a link, node or box drag.
  if (hovered && ImGui::IsMouseClicked(ImGuiMouseButton_Left)) {
    press_at_ = mouse;
    drag_moved_ = false;
    auto port = port_at(layouts, mouse, reach);
    auto node = node_at(layouts, mouse);
    if (port && !port->spot.is_input) {
      drag_ = Drag::kLink;
      link_from_ = {port->node, port->spot.port};
    } else if (port && port->spot.is_input) {
      const auto& inputs = state.doc.graph().nodes.at(port->node).inputs;
      auto linked = inputs.find(port->spot.port);
      if (linked != inputs.end()) {
        // Pick the link up from its input: it follows the mouse from its source.
        link_from_ = linked->second;
        (void)actions::unlink(state, port->node, port->spot.port);
        drag_ = Drag::kLink;
      }
    } else if (node) {
      if (io.KeyCtrl) {
        if (!state.selection.erase(*node)) state.selection.insert(*node);
      } else if (!state.selection.count(*node)) {
        actions::select(state, {*node});
      }
      if (ImGui::IsMouseDoubleClicked(ImGuiMouseButton_Left)) {
        const NodeType* type = state.doc.registry().find(state.doc.graph().nodes.at(*node).type);
        if (type != nullptr && !type->outputs.empty()) {
          (void)actions::select_output(state, {*node, type->outputs.front().name});
        }
      }
      drag_ = Drag::kNodes;
      drag_origins_.clear();
      for (const auto& id : state.selection) {
        drag_origins_[id] = node_position(state.doc.graph(), id);
      }
    } else {
      if (!io.KeyCtrl) state.selection.clear();
      drag_ = Drag::kBox;
    }
  }

  const bool left_down = ImGui::IsMouseDown(ImGuiMouseButton_Left);
  if (left_down && (std::fabs(mouse.x - press_at_.x) > 3 || std::fabs(mouse.y - press_at_.y) > 3)) {
    drag_moved_ = true;
  }

  if (drag_ == Drag::kNodes && left_down && drag_moved_) {
    std::map<std::string, Position> moved;
    for (const auto& [id, start] : drag_origins_) {
      moved[id] = {start.x + (mouse.x - press_at_.x) / view.zoom,
                   start.y + (mouse.y - press_at_.y) / view.zoom};
    }
    (void)actions::move(state, moved, /*gesture=*/true);
  }

  if (drag_ == Drag::kLink) {
    const NodeLayout* from_layout = nullptr;
    for (const auto& layout : layouts) {
      if (layout.id == link_from_.node) from_layout = &layout;
    }
    const PortSpot* from = from_layout ? find_spot(from_layout->outputs, link_from_.port) : nullptr;
    auto target = port_at(layouts, mouse, reach);
    std::string why;
    if (target && target->spot.is_input) {
      why = state.doc.why_not_link(link_from_, target->node, target->spot.port);
    }
    if (from != nullptr && drag_moved_) {
      ImU32 colour = !why.empty()                      ? IM_COL32(255, 90, 80, 255)
                     : target && target->spot.is_input ? IM_COL32(120, 230, 120, 255)
                                                       : IM_COL32(220, 220, 220, 255);
      draw_link(draw, from->at, target && target->spot.is_input ? target->spot.at : mouse, colour,
                view.zoom);
      if (!why.empty()) ImGui::SetTooltip("%s", why.c_str());
    }
    if (!left_down) {
      if (target && target->spot.is_input) {
        (void)actions::link(state, link_from_, target->node, target->spot.port);
      } else if (!drag_moved_) {
        (void)actions::select_output(state, link_from_);  // a click on an output views it
      }
      drag_ = Drag::kNone;
    }
  }

  if (drag_ == Drag::kBox) {
    Rect box{{std::min(press_at_.x, mouse.x), std::min(press_at_.y, mouse.y)},
             {std::max(press_at_.x, mouse.x), std::max(press_at_.y, mouse.y)}};
    if (drag_moved_) {
      draw->AddRectFilled(im(box.min), im(box.max), IM_COL32(120, 160, 255, 40));
      draw->AddRect(im(box.min), im(box.max), IM_COL32(120, 160, 255, 200));
    }
    if (!left_down) {
      if (drag_moved_) {
        std::vector<std::string> inside;
        for (const auto& layout : layouts) {
          if (box.overlaps(layout.rect)) inside.push_back(layout.id);
        }
        actions::select(state, inside, /*add=*/true);
      }
      drag_ = Drag::kNone;
    }
  }

  if (drag_ == Drag::kNodes && !left_down) {
    actions::end_gesture(state);
    drag_ = Drag::kNone;
  }
}

void Canvas::handle_keys(EditorState& state) {
  ImGuiIO& io = ImGui::GetIO();
  if (ImGui::IsKeyPressed(ImGui::GetKeyIndex(ImGuiKey_Delete)) ||
      ImGui::IsKeyPressed(ImGui::GetKeyIndex(ImGuiKey_Backspace))) {
    if (!state.selection.empty()) (void)actions::delete_selection(state);
  }
  if (io.KeyCtrl && ImGui::IsKeyPressed(GLFW_KEY_D, false)) {
    (void)actions::duplicate_selection(state);
  }
  if (!io.KeyCtrl && ImGui::IsKeyPressed(GLFW_KEY_F, false)) request_fit();
  if (!io.KeyCtrl && ImGui::IsKeyPressed(GLFW_KEY_C)) {
    actions::cycle_output(state, io.KeyShift ? -1 : +1);
  }
  if (ImGui::IsKeyPressed(ImGui::GetKeyIndex(ImGuiKey_Tab), false)) request_add_menu();
  if (!io.KeyCtrl && ImGui::IsKeyPressed(GLFW_KEY_1, false)) state.canvas.zoom = 1.0f;
}

void Canvas::draw_add_menu(EditorState& state) {
  if (add_menu_requested_) {
    Vec2 centre =
        state.canvas.to_canvas(origin_, {origin_.x + size_.x * 0.5f, origin_.y + size_.y * 0.5f});
    add_at_ = {centre.x, centre.y};
    add_filter_ = requested_filter_;
    ImGui::OpenPopup("add_node");
    add_menu_requested_ = false;
  }
  if (!ImGui::BeginPopup("add_node")) return;
  if (ImGui::IsWindowAppearing()) ImGui::SetKeyboardFocusHere();
  bool enter = ImGui::InputTextWithHint("##filter", "search nodes", &add_filter_,
                                        ImGuiInputTextFlags_EnterReturnsTrue);
  std::string needle = lower(add_filter_);
  std::map<std::string, std::vector<const NodeType*>> by_category;
  for (const auto& [name, type] : state.doc.registry().types()) {
    if (needle.empty() || lower(name).find(needle) != std::string::npos ||
        lower(type.description).find(needle) != std::string::npos ||
        lower(type.category).find(needle) != std::string::npos) {
      by_category[type.category.empty() ? "Other" : type.category].push_back(&type);
    }
  }
  std::string chosen;
  for (const auto& [category, types] : by_category) {
    if (enter && chosen.empty()) chosen = types.front()->name;
    ImGui::SetNextItemOpen(true, needle.empty() ? ImGuiCond_Appearing : ImGuiCond_Always);
    if (ImGui::TreeNode(category.c_str())) {
      for (const NodeType* type : types) {
        if (ImGui::MenuItem(type->name.c_str())) chosen = type->name;
        if (ImGui::IsItemHovered() && !type->description.empty()) {
          ImGui::SetTooltip("%s", type->description.c_str());
        }
      }
      ImGui::TreePop();
    }
  }
  if (by_category.empty()) ImGui::TextDisabled("no node matches");
  if (!chosen.empty()) {
    (void)actions::add_node(state, chosen, add_at_);
    ImGui::CloseCurrentPopup();
  }
  ImGui::EndPopup();
}

void Canvas::draw_node_menu(EditorState& state) {
  if (!ImGui::BeginPopup("node_menu")) return;
  if (menu_node_ && state.doc.graph().nodes.count(*menu_node_)) {
    const std::string id = *menu_node_;
    const NodeType* type = state.doc.registry().find(state.doc.graph().nodes.at(id).type);
    ImGui::TextDisabled("%s", id.c_str());
    if (type != nullptr) {
      for (const auto& port : type->outputs) {
        if (ImGui::MenuItem(("view " + port.name).c_str())) {
          (void)actions::select_output(state, {id, port.name});
        }
      }
      for (const auto& port : type->outputs) {
        if (ImGui::MenuItem(("make graph output: " + port.name).c_str())) {
          (void)actions::set_graph_output(state, {id, port.name});
        }
      }
    }
    ImGui::Separator();
    if (ImGui::MenuItem("duplicate", "Ctrl+D")) (void)actions::duplicate_selection(state);
    if (ImGui::MenuItem("delete", "Del")) (void)actions::delete_selection(state);
  }
  ImGui::EndPopup();
}

}  // namespace aq::editor
