// The node canvas, drawn with ImGui's draw lists: nodes with typed, coloured ports, links as
// curves, the viewed output ringed, GPU time and errors on the nodes. Mouse and keys:
//
//   left drag from an output to an input   link (refused links show why, in red)
//   left drag from a linked input          pick the link up: drop on another input or let go
//   click an output port / double-click    view that output in the viewer
//   left drag on a node / empty space      move the selection / box-select (Ctrl adds)
//   middle or right drag, wheel            pan, zoom around the cursor
//   right click / Tab                      add-node menu (searchable, by category) or node menu
//   Delete, Ctrl+D, F, C / Shift+C          delete, duplicate, fit, cycle the viewed output
//
// Every change goes through editor_actions.h.
#pragma once

#include "canvas_view.h"
#include "editor_state.h"

#include <aquarelle/core/evaluator.h>

#include <map>
#include <optional>
#include <string>
#include <vector>

namespace aq::editor {

// What the canvas shows on nodes besides the graph: timings and evaluation errors. A node the
// last evaluation reused keeps the time it took when it last ran, marked cached.
struct NodeFeedback {
  std::map<std::string, NodeTiming> timings;
  std::string error_node;
  std::string error;
};

class Canvas {
 public:
  // Draws into the current ImGui window's remaining content region.
  void draw(EditorState& state, const NodeFeedback& feedback);
  // The canvas as last drawn (screen space), for scripted mouse gestures.
  const std::vector<NodeLayout>& layouts() const { return layouts_; }
  Vec2 origin() const { return origin_; }
  Vec2 size() const { return size_; }
  // Fit all nodes into view on the next draw.
  void request_fit() { fit_requested_ = true; }
  // Opens the add-node menu at the canvas centre (menu bar, Tab).
  void request_add_menu(const std::string& filter = "") {
    add_menu_requested_ = true;
    requested_filter_ = filter;
  }

 private:
  enum class Drag { kNone, kNodes, kLink, kBox, kPan };

  void handle_mouse(EditorState& state, const std::vector<NodeLayout>& layouts, Vec2 origin);
  void handle_keys(EditorState& state);
  void draw_add_menu(EditorState& state);
  void draw_node_menu(EditorState& state);

  Drag drag_ = Drag::kNone;
  bool drag_moved_ = false;
  PortRef link_from_;
  Vec2 press_at_;
  std::map<std::string, Position> drag_origins_;
  std::optional<std::string> menu_node_;
  Position add_at_;
  std::string add_filter_;
  bool fit_requested_ = true;
  bool add_menu_requested_ = false;
  std::string requested_filter_;
  Vec2 size_;
  Vec2 origin_;
  std::vector<NodeLayout> layouts_;
};

}  // namespace aq::editor
