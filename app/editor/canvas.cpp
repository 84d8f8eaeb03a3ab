// The node canvas: drawing with ImGui draw lists and the mouse and key handling. See canvas.h.
#include "canvas.h"

#include "editor_actions.h"
#include "node_advice.h"
#include "node_search.h"

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
#include <utility>

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

void draw_link(ImDrawList* draw, Vec2 from, Vec2 to, ImU32 colour, float zoom) {
  float dx = std::max(std::fabs(to.x - from.x) * 0.5f, 30.0f * zoom);
  draw->AddBezierCubic(im(from), ImVec2(from.x + dx, from.y), ImVec2(to.x - dx, to.y), im(to),
                       colour, std::max(1.5f, 2.5f * zoom));
}

}  // namespace

void Canvas::text(ImDrawList* draw, Vec2 at, float zoom, ImU32 colour,
                  const std::string& label) const {
  const float pixels = kTextSize * zoom;
  if (pixels < 4.0f) return;  // too small to read: a blur of pixels helps nobody
  auto font = fonts_.find(text_raster_size(pixels));
  ImFont* chosen = font != fonts_.end() ? font->second : ImGui::GetFont();
  // Whole pixels: a glyph placed between pixels is resampled and goes soft.
  draw->AddText(chosen, pixels, ImVec2(std::round(at.x), std::round(at.y)), colour, label.c_str());
}

void Canvas::title(ImDrawList* draw, const Rect& header, float zoom, ImU32 colour,
                   const std::string& label) const {
  const float pixels = title_pixels(zoom);
  auto font = fonts_.find(text_raster_size(pixels));
  ImFont* chosen = font != fonts_.end() ? font->second : ImGui::GetFont();
  // Kept legible when the whole graph is fitted small: never under kMinTitlePixels, cut at
  // the node's edge rather than spilling over its neighbours.
  const float bottom = std::max(header.max.y, header.min.y + pixels + 2.0f);
  draw->PushClipRect(im(header.min), ImVec2(header.max.x, bottom), true);
  const float y = header.min.y + std::max(0.0f, (header.max.y - header.min.y - pixels) * 0.5f);
  draw->AddText(chosen, pixels,
                ImVec2(std::round(header.min.x + 4.0f + 2.0f * zoom), std::round(y)), colour,
                label.c_str());
  draw->PopClipRect();
}

Vec2 Canvas::text_size(float zoom, const std::string& label) const {
  const float pixels = kTextSize * zoom;
  auto font = fonts_.find(text_raster_size(pixels));
  ImFont* chosen = font != fonts_.end() ? font->second : ImGui::GetFont();
  return vec(chosen->CalcTextSizeA(pixels, FLT_MAX, 0, label.c_str()));
}

void Canvas::draw(EditorState& state, const NodeFeedback& feedback,
                  const std::vector<KeyChord>& chords) {
  const Graph& graph = state.doc.graph();
  const Registry& registry = state.doc.registry();
  ImVec2 available = ImGui::GetContentRegionAvail();
  size_ = {std::max(available.x, 50.0f), std::max(available.y, 50.0f)};
  origin_ = vec(ImGui::GetCursorScreenPos());
  CanvasView& view = state.canvas;
  const Rect bounds = graph_bounds(graph, registry);
  if (fit_requested_) {
    // Every node on screen (a readable minimum zoom left 10 of the flagship's 16 off it);
    // titles stay legible at any zoom (Canvas::title).
    view.fit_all(bounds, size_);
    fit_requested_ = false;
  }

  ImDrawList* draw = ImGui::GetWindowDrawList();
  ImVec2 lo = im(origin_);
  ImVec2 hi(origin_.x + size_.x, origin_.y + size_.y);
  draw->PushClipRect(lo, hi, true);
  draw->AddRectFilled(lo, hi, IM_COL32(32, 34, 38, 255));
  if (backdrop_texture_ != 0 && backdrop_width_ > 0 && backdrop_height_ > 0) {
    // The viewed image fitted into the canvas, dimmed so the nodes stay legible.
    const float scale = std::min(size_.x / backdrop_width_, size_.y / backdrop_height_);
    const ImVec2 extent(backdrop_width_ * scale, backdrop_height_ * scale);
    const ImVec2 at(lo.x + (size_.x - extent.x) * 0.5f, lo.y + (size_.y - extent.y) * 0.5f);
    draw->AddImage(reinterpret_cast<ImTextureID>(static_cast<intptr_t>(backdrop_texture_)), at,
                   ImVec2(at.x + extent.x, at.y + extent.y), ImVec2(0, 1), ImVec2(1, 0),
                   IM_COL32(255, 255, 255, 110));
  }
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

  draw_backdrops(state, draw);

  draw_groups(state, draw, layouts);

  // Links (to and from a collapsed group: at its port for the inner node's).
  for (const auto& [id, node] : graph.nodes) {
    for (const auto& [port, source] : node.inputs) {
      const PortSpot* out = find_port_spot(layouts, source.node, source.port, false);
      const PortSpot* in = find_port_spot(layouts, id, port, true);
      if (out == nullptr || in == nullptr) continue;
      // Through its reroute dots, if any.
      Vec2 from_at = out->at;
      for (const Position& dot : read_reroutes(graph, id, port)) {
        Vec2 at = view.to_screen(origin_, {dot.x, dot.y});
        draw_link(draw, from_at, at, port_colour(out->type), view.zoom);
        draw->AddCircleFilled(im(at), 5.0f * view.zoom + 1.0f, port_colour(out->type));
        from_at = at;
      }
      draw_link(draw, from_at, in->at, port_colour(out->type), view.zoom);
    }
  }

  // Nodes.
  for (const auto& layout : layouts) {
    if (layout.group) {
      draw_group_node(state, draw, layout, feedback);
    } else {
      draw_node(state, draw, layout, feedback);
    }
  }

  handle_mouse(state, layouts, origin_);
  layouts_ = std::move(layouts);
  draw_minimap(state, bounds);
  draw->PopClipRect();
  // Keys act on hover: no click into the canvas first.
  const bool over = ImGui::IsWindowHovered(ImGuiHoveredFlags_ChildWindows |
                                           ImGuiHoveredFlags_AllowWhenBlockedByActiveItem);
  if ((over || ImGui::IsWindowFocused(ImGuiFocusedFlags_ChildWindows)) &&
      !ImGui::GetIO().WantTextInput && !ImGui::IsPopupOpen("", ImGuiPopupFlags_AnyPopupId)) {
    handle_keys(state, chords);
  }
  draw_add_menu(state);
  draw_node_menu(state);
  draw_rename(state);
}

// One node (not a collapsed group): body, header, title, ports, timing footer, the reason it
// is marked on hover.
void Canvas::draw_node(EditorState& state, ImDrawList* draw, const NodeLayout& layout,
                       const NodeFeedback& feedback) {
  const Graph& graph = state.doc.graph();
  const Registry& registry = state.doc.registry();
  const auto shown = state.shown_output();
  const float z = state.canvas.zoom;
  const float rounding = 5.0f * z;
  const Node& node = graph.nodes.at(layout.id);
  const NodeType* type = registry.find(node.type);
  auto problems = state.doc.problems_of(layout.id);
  bool failed = !problems.empty() || feedback.error_node == layout.id || type == nullptr;
  bool selected = state.selection.count(layout.id) > 0;
  const bool bypassed = state.doc.bypassed(layout.id);
  draw->AddRectFilled(im(layout.rect.min), im(layout.rect.max),
                      bypassed ? IM_COL32(44, 44, 48, 240) : IM_COL32(58, 60, 66, 240), rounding);
  draw->AddRectFilled(im(layout.header.min), im(layout.header.max),
                      type ? category_colour(type->category) : IM_COL32(120, 40, 40, 255), rounding,
                      ImDrawFlags_RoundCornersTop);
  ImU32 border = failed     ? IM_COL32(255, 80, 70, 255)
                 : selected ? IM_COL32(255, 220, 120, 255)
                            : IM_COL32(20, 20, 22, 255);
  draw->AddRect(im(layout.rect.min), im(layout.rect.max), border, rounding, 0,
                failed || selected ? 2.5f : 1.0f);
  std::string title = layout.id == node.type ? layout.id : layout.id + " (" + node.type + ")";
  if (failed) title = "! " + title;
  this->title(draw, layout.header, z, IM_COL32(245, 245, 245, 255), title);
  if (bypassed) {
    // Nuke's mark of a disabled node: a diagonal across it.
    draw->AddLine(im(layout.rect.min), im(layout.rect.max), IM_COL32(230, 170, 60, 220), 2.0f * z);
  }
  for (const auto& spot : layout.inputs) {
    bool linked = node.inputs.count(spot.port) > 0;
    draw->AddCircleFilled(im(spot.at), NodeMetrics::kPortRadius * z,
                          linked ? port_colour(spot.type) : IM_COL32(70, 70, 76, 255));
    draw->AddCircle(im(spot.at), NodeMetrics::kPortRadius * z, port_colour(spot.type), 0, 1.5f);
    // A port holding several links (AQ_PORT_MULTI) says how many.
    const size_t links = node.inputs.count(spot.port);
    text(draw, {spot.at.x + 9 * z, spot.at.y - 7 * z}, z, IM_COL32(210, 210, 215, 255),
         links > 1 ? spot.port + " (" + std::to_string(links) + ")" : spot.port);
  }
  for (const auto& spot : layout.outputs) {
    draw->AddCircleFilled(im(spot.at), NodeMetrics::kPortRadius * z, port_colour(spot.type));
    if (shown && shown->node == layout.id && shown->port == spot.port) {
      draw->AddCircle(im(spot.at), (NodeMetrics::kPortRadius + 4) * z, IM_COL32(255, 255, 255, 255),
                      0, 2.0f);
    }
    if (state.compare && state.compare->node == layout.id && state.compare->port == spot.port) {
      // B of the viewer's A/B wipe.
      draw->AddCircle(im(spot.at), (NodeMetrics::kPortRadius + 7) * z, IM_COL32(255, 170, 60, 255),
                      0, 2.0f);
    }
    const Vec2 label = text_size(z, spot.port);
    text(draw, {spot.at.x - 9 * z - label.x, spot.at.y - 7 * z}, z, IM_COL32(210, 210, 215, 255),
         spot.port);
  }
  // Footer: GPU time of the last evaluation.
  std::string footer;
  auto timing = feedback.timings.find(layout.id);
  if (bypassed) {
    footer = "bypassed";
  } else if (feedback.error_node == layout.id) {
    footer = "failed";
  } else if (timing != feedback.timings.end()) {
    char text[64];
    std::snprintf(text, sizeof text, "gpu %.2f ms%s", timing->second.gpu_ms,
                  timing->second.cached ? "  (cached)" : "");
    footer = text;
  } else {
    footer = "not evaluated";
  }
  text(draw, {layout.rect.min.x + 6 * z, layout.rect.max.y - NodeMetrics::kFooter * z}, z,
       feedback.error_node == layout.id ? IM_COL32(255, 120, 110, 255)
                                        : IM_COL32(150, 200, 150, 255),
       footer);
  // The reason a node is marked, on hover: each message once.
  if (failed && ImGui::IsWindowHovered() && layout.rect.contains(vec(ImGui::GetMousePos()))) {
    const auto reasons =
        node_advice(state.doc, layout.id, feedback.error_node == layout.id ? feedback.error : "");
    std::string why;
    for (const auto& reason : reasons) why += (why.empty() ? "" : "\n") + reason;
    ImGui::SetTooltip("%s", why.c_str());
  }
}

void Canvas::handle_mouse(EditorState& state, const std::vector<NodeLayout>& layouts, Vec2 origin) {
  ImGuiIO& io = ImGui::GetIO();
  CanvasView& view = state.canvas;
  const Vec2 mouse = vec(io.MousePos);
  const bool hovered = ImGui::IsItemHovered();
  const std::optional<Press> press = std::exchange(press_, std::nullopt);

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
        add_on_link_ = link_at(state.doc.graph(), layouts, mouse, 6.0f, view.zoom);
        ImGui::OpenPopup("add_node");
      }
    }
    drag_ = Drag::kNone;
  }

  const Minimap map =
      minimap_for(graph_bounds(state.doc.graph(), state.doc.registry()), origin, size_);
  if (hovered && ImGui::IsMouseClicked(ImGuiMouseButton_Left) && map.box.contains(mouse)) {
    minimap_drag_ = true;
  }
  if (minimap_drag_) {
    if (ImGui::IsMouseDown(ImGuiMouseButton_Left)) {
      centre_on(view, map.to_canvas(mouse), size_);
    } else {
      minimap_drag_ = false;
    }
    return;
  }

  // Left button: press starts a link, node, dot or box drag, judged where and when the press
  // happened (a quick drag from a port has left it by the time this frame runs).
  if (hovered && ImGui::IsMouseClicked(ImGuiMouseButton_Left)) {
    const Vec2 at = press ? Vec2{press->x, press->y} : mouse;
    const bool twice =
        press ? press->double_click : ImGui::IsMouseDoubleClicked(ImGuiMouseButton_Left);
    begin_press(state, layouts, origin, at, twice);
  }
  continue_drag(state, layouts, origin);
}

// A left press at `mouse` (where it happened, see mouse_press.h): starts a link, node, dot,
// backdrop or box drag, or acts on a double-click (`twice`).
void Canvas::begin_press(EditorState& state, const std::vector<NodeLayout>& layouts, Vec2 origin,
                         Vec2 mouse, bool twice) {
  ImGuiIO& io = ImGui::GetIO();
  CanvasView& view = state.canvas;
  const float reach = std::max(NodeMetrics::kPortRadius * view.zoom + 4.0f, 8.0f);
  press_at_ = mouse;
  drag_moved_ = false;
  auto port = port_at(layouts, mouse, reach);
  auto node = node_at(layouts, mouse);
  auto dot = reroute_at(state.doc.graph(), view, origin, mouse, reach);
  if (dot && !port && !node) {
    if (twice) {
      actions::report(state, state.doc.remove_reroute(dot->node, dot->input, dot->index),
                      "removed a dot");
    } else {
      dragged_dot_ = *dot;
      drag_ = Drag::kDot;
    }
  } else if (twice && !port && !node &&
             link_at(state.doc.graph(), layouts, mouse, 6.0f, view.zoom)) {
    // A double-click on a link adds a reroute dot there.
    auto hit = link_at(state.doc.graph(), layouts, mouse, 6.0f, view.zoom);
    Vec2 at = view.to_canvas(origin, mouse);
    actions::report(state, state.doc.add_reroute(hit->node, hit->input, {at.x, at.y}),
                    "added a dot to the link into " + hit->node + "." + hit->input);
    drag_ = Drag::kNone;
  } else if (port && !port->spot.is_input) {
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
  } else if (!node && group_title_at(state, layouts, mouse)) {
    // The title of an expanded group: a double-click collapses it, a click selects its nodes.
    const Group group = *group_title_at(state, layouts, mouse);
    if (twice) {
      (void)actions::set_group_collapsed(state, group.name, true);
    } else {
      actions::select(state, group.nodes, io.KeyCtrl);
    }
    drag_ = Drag::kNone;
  } else if (!node && backdrop_title_at(state, mouse)) {
    backdrop_ = *backdrop_title_at(state, mouse);
    backdrop_moved_ = {0, 0};
    drag_ = Drag::kBackdrop;
    if (twice) {
      label_backdrop_ = true;
      label_text_ = read_backdrops(state.doc.graph())[backdrop_].label;
      drag_ = Drag::kNone;
    }
  } else if (node) {
    if (io.KeyCtrl) {
      if (!state.selection.erase(*node)) state.selection.insert(*node);
    } else if (!state.selection.count(*node)) {
      actions::select(state, {*node});
    }
    if (twice && group_name_of_item(*node)) {
      // A double-click opens a collapsed group.
      (void)actions::set_group_collapsed(state, *group_name_of_item(*node), false);
      drag_ = Drag::kNone;
      return;
    }
    if (twice) {
      const NodeType* type = state.doc.registry().find(state.doc.graph().nodes.at(*node).type);
      if (type != nullptr && !type->outputs.empty()) {
        (void)actions::select_output(state, {*node, type->outputs.front().name});
      }
    }
    drag_ = Drag::kNodes;
    drag_origins_.clear();
    for (const auto& id : state.selection) {
      drag_origins_[id] = item_position(state.doc.graph(), id);
    }
  } else {
    if (!io.KeyCtrl) actions::clear_selection(state);
    drag_ = Drag::kBox;
  }
}

// The drag under way (nodes, dot, backdrop, link, box) follows the mouse and ends on release.
void Canvas::continue_drag(EditorState& state, const std::vector<NodeLayout>& layouts,
                           Vec2 origin) {
  CanvasView& view = state.canvas;
  const Vec2 mouse = vec(ImGui::GetIO().MousePos);
  const float reach = std::max(NodeMetrics::kPortRadius * view.zoom + 4.0f, 8.0f);
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

  if (drag_ == Drag::kDot) {
    if (left_down && drag_moved_) {
      Vec2 at = view.to_canvas(origin, mouse);
      (void)state.doc.move_reroute(dragged_dot_.node, dragged_dot_.input, dragged_dot_.index,
                                   {std::round(at.x), std::round(at.y)}, "dot");
    }
    if (!left_down) {
      actions::end_gesture(state);
      drag_ = Drag::kNone;
    }
  }

  if (drag_ == Drag::kBackdrop) {
    if (left_down && drag_moved_) {
      const Vec2 total{std::round((mouse.x - press_at_.x) / view.zoom),
                       std::round((mouse.y - press_at_.y) / view.zoom)};
      const Position step{total.x - backdrop_moved_.x, total.y - backdrop_moved_.y};
      if (step.x != 0 || step.y != 0) {
        (void)state.doc.move_backdrop(backdrop_, step, "backdrop");
        backdrop_moved_ = total;
      }
    }
    if (!left_down) {
      actions::end_gesture(state);
      drag_ = Drag::kNone;
    }
  }

  if (drag_ == Drag::kLink) continue_link(state, layouts, mouse, reach, left_down);
  if (drag_ == Drag::kBox) continue_box(state, layouts, mouse, left_down);
  if (drag_ == Drag::kNodes && !left_down) {
    actions::end_gesture(state);
    drag_ = Drag::kNone;
    // One unlinked node let go over a link is spliced into it (Blender's drop on a link).
    if (drag_moved_ && drag_origins_.size() == 1) {
      const std::string id = drag_origins_.begin()->first;
      const Graph& graph = state.doc.graph();
      bool linked = graph.nodes.count(id) && !graph.nodes.at(id).inputs.empty();
      for (const auto& [other, node] : graph.nodes) {
        for (const auto& [in, from] : node.inputs) linked = linked || from.node == id;
      }
      if (!linked && graph.nodes.count(id)) {
        if (auto hit = link_at(graph, layouts, mouse, 8.0f, view.zoom); hit && hit->node != id) {
          Status dropped = state.doc.splice_into_link(id, hit->node, hit->input);
          actions::report(state, dropped,
                          "dropped " + id + " on the link into " + hit->node + "." + hit->input);
        }
      }
    }
  }
}

void Canvas::continue_link(EditorState& state, const std::vector<NodeLayout>& layouts, Vec2 mouse,
                           float reach, bool left_down) {
  ImDrawList* draw = ImGui::GetWindowDrawList();
  const CanvasView& view = state.canvas;
  const PortSpot* from = find_port_spot(layouts, link_from_.node, link_from_.port, false);
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
    } else if (!drag_moved_ && ImGui::GetIO().KeyShift) {
      (void)actions::compare_with(state, link_from_);  // shift+click: B of the A/B wipe
    } else if (!drag_moved_) {
      (void)actions::select_output(state, link_from_);  // a click on an output views it
    }
    drag_ = Drag::kNone;
  }
}

void Canvas::continue_box(EditorState& state, const std::vector<NodeLayout>& layouts, Vec2 mouse,
                          bool left_down) {
  ImDrawList* draw = ImGui::GetWindowDrawList();
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

void Canvas::handle_keys(EditorState& state, const std::vector<KeyChord>& chords) {
  const Vec2 mouse = vec(ImGui::GetIO().MousePos);
  const bool over = Rect{origin_, {origin_.x + size_.x, origin_.y + size_.y}}.contains(mouse);
  const Vec2 anchor = over ? mouse : Vec2{origin_.x + size_.x * 0.5f, origin_.y + size_.y * 0.5f};
  for (const KeyChord& chord : chords) {
    const bool plain = !chord.ctrl && !chord.alt;
    switch (chord.key) {
      case GLFW_KEY_DELETE:
      case GLFW_KEY_BACKSPACE:
        if (!state.selection.empty()) (void)actions::delete_selection(state);
        break;
      case GLFW_KEY_D:
        if (chord.ctrl) {
          (void)actions::duplicate_selection(state);
        } else if (plain) {
          (void)actions::toggle_bypass(state);
        }
        break;
      case GLFW_KEY_C:
        if (chord.ctrl) {
          std::string copied = actions::copy_selection(state);
          if (!copied.empty()) ImGui::SetClipboardText(copied.c_str());
        } else if (plain) {
          actions::cycle_output(state, chord.shift ? -1 : +1);
        }
        break;
      case GLFW_KEY_V:
        if (chord.ctrl) {
          const char* text = ImGui::GetClipboardText();
          Vec2 at = state.canvas.to_canvas(origin_, anchor);
          (void)actions::paste(state, text != nullptr ? text : "", Position{at.x, at.y});
        }
        break;
      case GLFW_KEY_F:
        if (plain) request_fit();
        break;
      case GLFW_KEY_1:
        if (plain) state.canvas.zoom_to(origin_, anchor, 1.0f);
        break;
      case GLFW_KEY_L:
        if (plain) (void)actions::auto_layout(state);
        break;
      case GLFW_KEY_B:
        if (plain) (void)actions::backdrop_around_selection(state);
        break;
      case GLFW_KEY_F2:
        if (state.selection.size() == 1) {
          rename_node_ = *state.selection.begin();
          // A collapsed group is renamed by its name.
          rename_text_ = group_name_of_item(rename_node_).value_or(rename_node_);
        }
        break;
      case GLFW_KEY_TAB:
        if (plain) request_add_menu();
        break;
      default:
        break;
    }
  }
}

void Canvas::draw_minimap(EditorState& state, const Rect& bounds) {
  const Graph& graph = state.doc.graph();
  if (graph.nodes.empty()) return;
  const CanvasView& view = state.canvas;
  // Only when part of the graph is out of view.
  Vec2 lo = view.to_screen(origin_, bounds.min);
  Vec2 hi = view.to_screen(origin_, bounds.max);
  if (lo.x >= origin_.x && lo.y >= origin_.y && hi.x <= origin_.x + size_.x &&
      hi.y <= origin_.y + size_.y) {
    return;
  }
  const Minimap map = minimap_for(bounds, origin_, size_);
  ImDrawList* draw = ImGui::GetWindowDrawList();
  draw->AddRectFilled(im(map.box.min), im(map.box.max), IM_COL32(20, 21, 24, 220), 4.0f);
  draw->AddRect(im(map.box.min), im(map.box.max), IM_COL32(90, 92, 100, 255), 4.0f);
  // What the canvas shows: a collapsed group as one box.
  CanvasView identity;
  identity.pan = {0, 0};
  identity.zoom = 1.0f;
  for (const auto& layout : layout_graph(graph, state.doc.registry(), identity, {0, 0})) {
    draw->AddRectFilled(im(map.to_minimap(layout.rect.min)), im(map.to_minimap(layout.rect.max)),
                        state.selection.count(layout.id) ? IM_COL32(255, 220, 120, 255)
                                                         : IM_COL32(140, 145, 160, 255));
  }
  // The part of the canvas on screen.
  Vec2 view_min = view.to_canvas(origin_, origin_);
  Vec2 view_max = view.to_canvas(origin_, {origin_.x + size_.x, origin_.y + size_.y});
  draw->PushClipRect(im(map.box.min), im(map.box.max), true);
  draw->AddRect(im(map.to_minimap(view_min)), im(map.to_minimap(view_max)),
                IM_COL32(255, 255, 255, 200), 0.0f, 0, 1.5f);
  draw->PopClipRect();
}

std::optional<size_t> Canvas::backdrop_title_at(const EditorState& state, Vec2 screen) const {
  const auto backdrops = read_backdrops(state.doc.graph());
  const CanvasView& view = state.canvas;
  for (size_t i = backdrops.size(); i-- > 0;) {
    const Backdrop& b = backdrops[i];
    Vec2 lo = view.to_screen(origin_, {b.at.x, b.at.y});
    Rect title{lo, {lo.x + b.width * view.zoom, lo.y + 30.0f * view.zoom}};
    if (title.contains(screen)) return i;
  }
  return std::nullopt;
}

void Canvas::draw_backdrops(EditorState& state, ImDrawList* draw) {
  const CanvasView& view = state.canvas;
  const float z = view.zoom;
  const auto backdrops = read_backdrops(state.doc.graph());
  for (const auto& b : backdrops) {
    Vec2 lo = view.to_screen(origin_, {b.at.x, b.at.y});
    Vec2 hi = view.to_screen(origin_, {b.at.x + b.width, b.at.y + b.height});
    draw->AddRectFilled(im(lo), im(hi), IM_COL32(70, 80, 96, 110), 6.0f * z);
    draw->AddRectFilled(im(lo), ImVec2(hi.x, lo.y + 30.0f * z), IM_COL32(88, 102, 124, 200),
                        6.0f * z, ImDrawFlags_RoundCornersTop);
    draw->AddRect(im(lo), im(hi), IM_COL32(120, 140, 170, 200), 6.0f * z);
    text(draw, {lo.x + 8 * z, lo.y + 6 * z}, z * 1.4f, IM_COL32(235, 240, 250, 255), b.label);
  }
  if (label_backdrop_ && !ImGui::IsPopupOpen("backdrop_label")) {
    ImGui::OpenPopup("backdrop_label");
  }
  if (ImGui::BeginPopup("backdrop_label")) {
    if (ImGui::IsWindowAppearing()) ImGui::SetKeyboardFocusHere();
    if (ImGui::InputText("label", &label_text_, ImGuiInputTextFlags_EnterReturnsTrue)) {
      (void)state.doc.set_backdrop_label(backdrop_, label_text_);
      label_backdrop_ = false;
      ImGui::CloseCurrentPopup();
    }
    if (ImGui::Button("delete backdrop")) {
      (void)state.doc.remove_backdrop(backdrop_);
      label_backdrop_ = false;
      ImGui::CloseCurrentPopup();
    }
    ImGui::EndPopup();
  } else {
    label_backdrop_ = false;
  }
}

void Canvas::draw_rename(EditorState& state) {
  if (!rename_node_.empty() && !ImGui::IsPopupOpen("rename_node")) {
    ImGui::OpenPopup("rename_node");
  }
  if (!ImGui::BeginPopup("rename_node")) {
    rename_node_.clear();
    return;
  }
  ImGui::Text("rename %s", rename_node_.c_str());
  if (ImGui::IsWindowAppearing()) ImGui::SetKeyboardFocusHere();
  if (ImGui::InputText("##rename", &rename_text_, ImGuiInputTextFlags_EnterReturnsTrue)) {
    if (actions::rename(state, rename_node_, rename_text_)) {
      rename_node_.clear();
      ImGui::CloseCurrentPopup();
    }
  }
  if (ImGui::IsKeyPressed(ImGui::GetKeyIndex(ImGuiKey_Escape))) {
    rename_node_.clear();
    ImGui::CloseCurrentPopup();
  }
  ImGui::EndPopup();
}

void Canvas::draw_add_menu_categories(EditorState& state, std::string* chosen) {
  std::map<std::string, std::vector<const NodeType*>> by_category;
  for (const auto& [name, type] : state.doc.registry().types()) {
    by_category[type.category.empty() ? "Other" : type.category].push_back(&type);
  }
  for (const auto& [category, types] : by_category) {
    ImGui::SetNextItemOpen(true, ImGuiCond_Appearing);
    if (ImGui::TreeNode(category.c_str())) {
      for (const NodeType* type : types) {
        if (ImGui::MenuItem(type->name.c_str())) *chosen = type->name;
        if (ImGui::IsItemHovered() && !type->description.empty()) {
          ImGui::SetTooltip("%s", type->description.c_str());
        }
      }
      ImGui::TreePop();
    }
  }
}

void Canvas::draw_add_menu(EditorState& state) {
  if (add_menu_requested_) {
    // At the cursor when it is over the canvas (Tab), else at the centre (menu bar).
    const Vec2 mouse = vec(ImGui::GetIO().MousePos);
    const bool over = Rect{origin_, {origin_.x + size_.x, origin_.y + size_.y}}.contains(mouse);
    const Vec2 anchor = over ? mouse : Vec2{origin_.x + size_.x * 0.5f, origin_.y + size_.y * 0.5f};
    Vec2 at = state.canvas.to_canvas(origin_, anchor);
    add_at_ = {at.x, at.y};
    add_on_link_ =
        over ? link_at(state.doc.graph(), layouts_, mouse, 6.0f, state.canvas.zoom) : std::nullopt;
    add_filter_ = requested_filter_;
    ImGui::OpenPopup("add_node");
    add_menu_requested_ = false;
  }
  if (!ImGui::BeginPopup("add_node")) return;
  if (ImGui::IsWindowAppearing()) ImGui::SetKeyboardFocusHere();
  bool enter = ImGui::InputTextWithHint("##filter", "search nodes", &add_filter_,
                                        ImGuiInputTextFlags_EnterReturnsTrue);
  std::string chosen;
  if (!add_filter_.empty()) {
    // Typed: one list, best match first (names before descriptions); Enter adds the first.
    const std::vector<const NodeType*> found = search_node_types(state.doc.registry(), add_filter_);
    if (enter && !found.empty()) chosen = found.front()->name;
    for (const NodeType* type : found) {
      if (ImGui::MenuItem(type->name.c_str(), type->category.c_str())) chosen = type->name;
      if (ImGui::IsItemHovered() && !type->description.empty()) {
        ImGui::SetTooltip("%s", type->description.c_str());
      }
    }
    if (found.empty()) ImGui::TextDisabled("no node matches");
  } else {
    draw_add_menu_categories(state, &chosen);
  }
  if (!chosen.empty()) {
    if (add_on_link_) {
      (void)actions::insert_on_link(state, chosen, add_at_, add_on_link_->node,
                                    add_on_link_->input);
    } else {
      (void)actions::add_node_at_cursor(state, chosen, add_at_);
    }
    add_on_link_.reset();
    ImGui::CloseCurrentPopup();
  }
  ImGui::EndPopup();
}

void Canvas::draw_node_menu(EditorState& state) {
  if (!ImGui::BeginPopup("node_menu")) return;
  if (menu_node_ && group_name_of_item(*menu_node_)) {
    const std::string name = *group_name_of_item(*menu_node_);
    ImGui::TextDisabled("group %s", name.c_str());
    if (ImGui::MenuItem("expand")) (void)actions::set_group_collapsed(state, name, false);
    if (ImGui::MenuItem("rename...", "F2")) {
      rename_node_ = *menu_node_;
      rename_text_ = name;
    }
    if (ImGui::MenuItem("ungroup", "Ctrl+Alt+G")) (void)actions::ungroup_selection(state);
    if (ImGui::MenuItem("delete its nodes", "Del")) (void)actions::delete_selection(state);
  } else if (menu_node_ && state.doc.graph().nodes.count(*menu_node_)) {
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
        if (ImGui::MenuItem(("compare with: " + port.name).c_str(), "shift+click")) {
          (void)actions::compare_with(state, PortRef{id, port.name});
        }
      }
      for (const auto& port : type->outputs) {
        if (ImGui::MenuItem(("make graph output: " + port.name).c_str())) {
          (void)actions::set_graph_output(state, {id, port.name});
        }
      }
    }
    ImGui::Separator();
    if (ImGui::MenuItem("rename...", "F2")) {
      rename_node_ = id;
      rename_text_ = id;
    }
    if (ImGui::MenuItem(state.doc.bypassed(id) ? "enable" : "bypass", "D")) {
      (void)actions::toggle_bypass(state);
    }
    if (ImGui::MenuItem("group", "Ctrl+G")) (void)actions::group_selection(state);
    if (ImGui::MenuItem("ungroup", "Ctrl+Alt+G")) (void)actions::ungroup_selection(state);
    if (ImGui::MenuItem("copy", "Ctrl+C")) {
      std::string copied = actions::copy_selection(state);
      if (!copied.empty()) ImGui::SetClipboardText(copied.c_str());
    }
    if (ImGui::MenuItem("duplicate", "Ctrl+D")) (void)actions::duplicate_selection(state);
    if (ImGui::MenuItem("delete", "Del")) (void)actions::delete_selection(state);
  }
  ImGui::EndPopup();
}

std::optional<Rect> Canvas::expanded_group_frame(const std::vector<NodeLayout>& layouts,
                                                 const Group& group) const {
  if (group.collapsed) return std::nullopt;
  Rect box{{1e30f, 1e30f}, {-1e30f, -1e30f}};
  for (const auto& layout : layouts) {
    if (std::find(group.nodes.begin(), group.nodes.end(), layout.id) == group.nodes.end()) continue;
    box.min = {std::min(box.min.x, layout.rect.min.x), std::min(box.min.y, layout.rect.min.y)};
    box.max = {std::max(box.max.x, layout.rect.max.x), std::max(box.max.y, layout.rect.max.y)};
  }
  if (box.min.x > box.max.x) return std::nullopt;
  return box;
}

std::optional<Group> Canvas::group_title_at(const EditorState& state,
                                            const std::vector<NodeLayout>& layouts,
                                            Vec2 screen) const {
  const float z = state.canvas.zoom;
  for (const auto& group : read_groups(state.doc.graph())) {
    auto frame = expanded_group_frame(layouts, group);
    if (!frame) continue;
    Rect title{{frame->min.x - 12 * z, frame->min.y - 40 * z},
               {frame->max.x + 12 * z, frame->min.y - 12 * z}};
    if (title.contains(screen)) return group;
  }
  return std::nullopt;
}

void Canvas::draw_groups(EditorState& state, ImDrawList* draw,
                         const std::vector<NodeLayout>& layouts) {
  // An expanded group: a dashed-looking frame around its nodes, its name in the title bar.
  const float z = state.canvas.zoom;
  for (const auto& group : read_groups(state.doc.graph())) {
    auto frame = expanded_group_frame(layouts, group);
    if (!frame) continue;
    const ImVec2 lo(frame->min.x - 12 * z, frame->min.y - 40 * z);
    const ImVec2 hi(frame->max.x + 12 * z, frame->max.y + 12 * z);
    draw->AddRectFilled(lo, hi, IM_COL32(90, 70, 120, 60), 6.0f * z);
    draw->AddRectFilled(lo, ImVec2(hi.x, lo.y + 28 * z), IM_COL32(110, 84, 150, 200), 6.0f * z,
                        ImDrawFlags_RoundCornersTop);
    draw->AddRect(lo, hi, IM_COL32(160, 130, 210, 220), 6.0f * z, 0, 1.5f);
    text(draw, {lo.x + 8 * z, lo.y + 6 * z}, z, IM_COL32(240, 235, 250, 255),
         group.name + "  (group, double-click to collapse)");
  }
}

void Canvas::draw_group_node(EditorState& state, ImDrawList* draw, const NodeLayout& layout,
                             const NodeFeedback& feedback) {
  const float z = state.canvas.zoom;
  const float rounding = 5.0f * z;
  const bool selected = state.selection.count(layout.id) > 0;
  bool failed = false;
  double gpu_ms = 0;
  for (const auto& id : layout.members) {
    failed = failed || !state.doc.problems_of(id).empty() || feedback.error_node == id;
    if (auto timing = feedback.timings.find(id); timing != feedback.timings.end()) {
      gpu_ms += timing->second.gpu_ms;
    }
  }
  draw->AddRectFilled(im(layout.rect.min), im(layout.rect.max), IM_COL32(62, 56, 74, 245),
                      rounding);
  draw->AddRectFilled(im(layout.header.min), im(layout.header.max), IM_COL32(110, 84, 150, 255),
                      rounding, ImDrawFlags_RoundCornersTop);
  const ImU32 border = failed     ? IM_COL32(255, 80, 70, 255)
                       : selected ? IM_COL32(255, 220, 120, 255)
                                  : IM_COL32(160, 130, 210, 255);
  draw->AddRect(im(layout.rect.min), im(layout.rect.max), border, rounding, 0,
                failed || selected ? 2.5f : 1.5f);
  const std::string name = group_name_of_item(layout.id).value_or(layout.id);
  title(draw, layout.header, z, IM_COL32(245, 245, 245, 255),
        (failed ? "! " : "") + name + " (" + std::to_string(layout.members.size()) + " nodes)");
  const auto shown = state.shown_output();
  const Graph& graph = state.doc.graph();
  for (const auto& spot : layout.inputs) {
    const bool linked = graph.nodes.at(spot.node).inputs.count(spot.port) > 0;
    draw->AddCircleFilled(im(spot.at), NodeMetrics::kPortRadius * z,
                          linked ? port_colour(spot.type) : IM_COL32(70, 70, 76, 255));
    draw->AddCircle(im(spot.at), NodeMetrics::kPortRadius * z, port_colour(spot.type), 0, 1.5f);
    text(draw, {spot.at.x + 9 * z, spot.at.y - 7 * z}, z, IM_COL32(210, 210, 215, 255),
         spot.node + "." + spot.port);
  }
  for (const auto& spot : layout.outputs) {
    draw->AddCircleFilled(im(spot.at), NodeMetrics::kPortRadius * z, port_colour(spot.type));
    if (shown && shown->node == spot.node && shown->port == spot.port) {
      draw->AddCircle(im(spot.at), (NodeMetrics::kPortRadius + 4) * z, IM_COL32(255, 255, 255, 255),
                      0, 2.0f);
    }
    if (state.compare && state.compare->node == spot.node && state.compare->port == spot.port) {
      draw->AddCircle(im(spot.at), (NodeMetrics::kPortRadius + 7) * z, IM_COL32(255, 170, 60, 255),
                      0, 2.0f);
    }
    const std::string label = spot.node + "." + spot.port;
    const Vec2 size = text_size(z, label);
    text(draw, {spot.at.x - 9 * z - size.x, spot.at.y - 7 * z}, z, IM_COL32(210, 210, 215, 255),
         label);
  }
  // Why it is marked, on hover: its nodes' reasons, each named.
  if (failed && ImGui::IsWindowHovered() && layout.rect.contains(vec(ImGui::GetMousePos()))) {
    std::string why;
    for (const auto& id : layout.members) {
      for (const auto& reason :
           node_advice(state.doc, id, feedback.error_node == id ? feedback.error : "")) {
        why += (why.empty() ? "" : "\n") + id + ": " + reason;
      }
    }
    if (!why.empty()) ImGui::SetTooltip("%s", why.c_str());
  }
  char footer[64];
  std::snprintf(footer, sizeof footer, "group  gpu %.2f ms", gpu_ms);
  text(draw, {layout.rect.min.x + 6 * z, layout.rect.max.y - NodeMetrics::kFooter * z}, z,
       IM_COL32(190, 170, 220, 255), footer);
}

}  // namespace aq::editor
