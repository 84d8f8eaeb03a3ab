// The node canvas, drawn with ImGui's draw lists: nodes with typed, coloured ports, links as
// curves, the viewed output ringed, GPU time and errors on the nodes. Mouse and keys:
//
//   left drag from an output to an input   link (refused links show why, in red)
//   left drag from a linked input          pick the link up: drop on another input or let go
//   click an output port / double-click    view that output in the viewer
//   left drag on a node / empty space      move the selection / box-select (Ctrl adds)
//   middle or right drag, wheel            pan, zoom around the cursor
//   right click / Tab                      add-node menu at the cursor (searchable, by category):
//                                          inserted after the one selected node, or onto the
//                                          link under the cursor; or the node menu
//   Delete, Ctrl+D, F, 1, C / Shift+C       delete, duplicate, fit, 1:1 at the cursor, cycle output
//   Ctrl+C / Ctrl+V, D, F2, L, B            copy / paste (system clipboard, graph JSON), bypass,
//                                          rename, auto-layout, backdrop around the selection
//   drag a backdrop's title bar            moves it with the nodes on it; double-click: label
//   double-click a link / a dot            adds a reroute dot there / removes it; drag a dot
//   minimap (bottom right)                 click or drag to move the view
//
// Keys act while the mouse is over the canvas (no click needed) and come from a queue of key
// presses the window collected (KeyChord), so a chord pressed and released between two frames
// still counts.
//
// Every change goes through editor_actions.h.
#pragma once

#include "canvas_view.h"
#include "editor_state.h"
#include "mouse_press.h"

#include <aquarelle/core/evaluator.h>
#include <imgui.h>

#include <map>
#include <optional>
#include <string>
#include <vector>

namespace aq::editor {

// What the canvas shows on nodes besides the graph: timings and evaluation errors. A node the
// last evaluation reused keeps the time it took when it last ran, marked cached.
// One key press as GLFW reported it, with the modifiers held at that moment.
struct KeyChord {
  int key = 0;  // GLFW_KEY_*
  bool ctrl = false;
  bool shift = false;
  bool alt = false;
};

struct NodeFeedback {
  std::map<std::string, NodeTiming> timings;
  std::string error_node;
  std::string error;
};

class Canvas {
 public:
  // Draws into the current ImGui window's remaining content region; `chords` are this frame's
  // key presses (the canvas takes its own when the mouse is over it or it has focus).
  void draw(EditorState& state, const NodeFeedback& feedback,
            const std::vector<KeyChord>& chords = {});
  // The viewer's picture drawn dimmed behind the nodes (Blender's backdrop); texture 0: none.
  void set_backdrop_image(unsigned texture, int width, int height) {
    backdrop_texture_ = texture;
    backdrop_width_ = width;
    backdrop_height_ = height;
  }
  // Fonts rasterised at kTextRasterSizes (canvas_view.h), for crisp text at every zoom.
  void set_fonts(std::map<float, ImFont*> fonts) { fonts_ = std::move(fonts); }
  // The canvas as last drawn (screen space), for scripted mouse gestures.
  const std::vector<NodeLayout>& layouts() const { return layouts_; }
  Vec2 origin() const { return origin_; }
  Vec2 size() const { return size_; }
  // Fit every node into view on the next draw (`F`, View > Fit graph); titles stay legible.
  // `whole` is kept for scripts: both fit every node.
  void request_fit(bool /*whole*/ = false) { fit_requested_ = true; }
  // The left press of this frame as it happened (place, double-click), from the window's
  // callback or a scripted gesture; without it the canvas uses ImGui's own.
  void set_press(std::optional<Press> press) { press_ = press; }
  // Opens the add-node menu at the canvas centre (menu bar, Tab).
  void request_add_menu(const std::string& filter = "") {
    add_menu_requested_ = true;
    requested_filter_ = filter;
  }

 private:
  enum class Drag { kNone, kNodes, kLink, kBox, kPan, kBackdrop, kDot };

  void draw_node(EditorState& state, ImDrawList* draw, const NodeLayout& layout,
                 const NodeFeedback& feedback);
  void handle_mouse(EditorState& state, const std::vector<NodeLayout>& layouts, Vec2 origin);
  void begin_press(EditorState& state, const std::vector<NodeLayout>& layouts, Vec2 origin,
                   Vec2 mouse, bool twice);
  void continue_drag(EditorState& state, const std::vector<NodeLayout>& layouts, Vec2 origin);
  void continue_link(EditorState& state, const std::vector<NodeLayout>& layouts, Vec2 mouse,
                     float reach, bool left_down);
  void continue_box(EditorState& state, const std::vector<NodeLayout>& layouts, Vec2 mouse,
                    bool left_down);
  void handle_keys(EditorState& state, const std::vector<KeyChord>& chords);
  void draw_minimap(EditorState& state, const Rect& bounds);
  void draw_rename(EditorState& state);
  void draw_backdrops(EditorState& state, ImDrawList* draw);
  // Node groups: frames around expanded ones, a collapsed one as one node.
  void draw_groups(EditorState& state, ImDrawList* draw, const std::vector<NodeLayout>& layouts);
  void draw_group_node(EditorState& state, ImDrawList* draw, const NodeLayout& layout,
                       const NodeFeedback& feedback);
  std::optional<Rect> expanded_group_frame(const std::vector<NodeLayout>& layouts,
                                           const Group& group) const;
  std::optional<Group> group_title_at(const EditorState& state,
                                      const std::vector<NodeLayout>& layouts, Vec2 screen) const;
  std::optional<size_t> backdrop_title_at(const EditorState& state, Vec2 screen) const;
  void text(ImDrawList* draw, Vec2 at, float zoom, ImU32 colour, const std::string& text) const;
  // A node's title in its header: at least kMinTitlePixels tall, clipped to the header.
  void title(ImDrawList* draw, const Rect& header, float zoom, ImU32 colour,
             const std::string& label) const;
  Vec2 text_size(float zoom, const std::string& text) const;
  void draw_add_menu(EditorState& state);
  // The add menu before anything is typed: every type, by category.
  void draw_add_menu_categories(EditorState& state, std::string* chosen);
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
  std::optional<Press> press_;  // this frame's left press as it happened (set_press)
  bool add_menu_requested_ = false;
  std::string requested_filter_;
  std::optional<LinkHit> add_on_link_;  // the add menu opened over a link: insert on it
  std::string rename_node_;             // the rename prompt's node ("" when closed)
  std::string rename_text_;
  bool minimap_drag_ = false;
  size_t backdrop_ = 0;  // the backdrop being dragged or labelled
  Vec2 backdrop_moved_;  // whole canvas units already applied during the drag
  bool label_backdrop_ = false;
  RerouteHit dragged_dot_;
  std::string label_text_;
  std::map<float, ImFont*> fonts_;
  unsigned backdrop_texture_ = 0;
  int backdrop_width_ = 0;
  int backdrop_height_ = 0;
  Vec2 size_;
  Vec2 origin_;
  std::vector<NodeLayout> layouts_;
};

}  // namespace aq::editor
