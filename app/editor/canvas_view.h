// The canvas's geometry without ImGui: where a node, its ports and its links sit on screen for
// a given pan and zoom, and what lies under a point. The canvas drawing and the mouse handling
// both read it, so what is drawn is exactly what is hit.
#pragma once

#include "document.h"

#include <aquarelle/core/graph.h>
#include <aquarelle/core/registry.h>

#include <optional>
#include <string>
#include <vector>

namespace aq::editor {

struct Vec2 {
  float x = 0;
  float y = 0;
};

struct Rect {
  Vec2 min;
  Vec2 max;
  bool contains(Vec2 p) const {
    return p.x >= min.x && p.x <= max.x && p.y >= min.y && p.y <= max.y;
  }
  bool overlaps(const Rect& o) const {
    return min.x <= o.max.x && o.min.x <= max.x && min.y <= o.max.y && o.min.y <= max.y;
  }
};

// Canvas units are the positions saved in the graph; screen = origin + pan + canvas * zoom.
struct CanvasView {
  Vec2 pan{40, 40};
  float zoom = 1.0f;
  static constexpr float kMinZoom = 0.2f;
  static constexpr float kMaxZoom = 3.0f;
  // Fit never goes below this: node text stays readable and the user pans the rest.
  static constexpr float kReadableZoom = 0.7f;

  Vec2 to_screen(Vec2 origin, Vec2 canvas) const {
    return {origin.x + pan.x + canvas.x * zoom, origin.y + pan.y + canvas.y * zoom};
  }
  Vec2 to_canvas(Vec2 origin, Vec2 screen) const {
    return {(screen.x - origin.x - pan.x) / zoom, (screen.y - origin.y - pan.y) / zoom};
  }
  // Zooms by `factor` keeping the canvas point under `screen` where it is.
  void zoom_at(Vec2 origin, Vec2 screen, float factor);
  // Sets the zoom keeping the canvas point under `screen` where it is (`1` zooms 1:1 there).
  void zoom_to(Vec2 origin, Vec2 screen, float new_zoom);
  // Pan and zoom so that `bounds` (canvas units) fills `size` (screen) with a margin, at a
  // readable zoom at least: a graph too big for that shows its left end (`focus`, a canvas
  // point, when given, is kept in view), the rest a pan away.
  void fit(Rect bounds, Vec2 size, std::optional<Vec2> focus = std::nullopt,
           float min_zoom = kReadableZoom);
  // `F`: every node in view (down to kMinZoom; titles stay legible, see title_pixels).
  void fit_all(Rect bounds, Vec2 size) { fit(bounds, size, std::nullopt, kMinZoom); }
};

// Node geometry in canvas units.
struct NodeMetrics {
  static constexpr float kWidth = 170.0f;
  static constexpr float kHeader = 24.0f;
  static constexpr float kRow = 20.0f;
  static constexpr float kFooter = 18.0f;  // GPU time line
  static constexpr float kPortRadius = 5.5f;
};

struct PortSpot {
  std::string node;  // the node the port belongs to (for a collapsed group: the inner node)
  std::string port;
  bool is_input = false;
  aq_port_type type = AQ_PORT_IMAGE;
  Vec2 at;  // screen
};

struct NodeLayout {
  std::string id;  // a node id, or group_item_id(name) for a collapsed group
  bool group = false;
  std::vector<std::string> members;  // a collapsed group's nodes
  Position position;                 // canvas units
  Rect rect;                         // screen
  Rect header;
  std::vector<PortSpot> inputs;
  std::vector<PortSpot> outputs;
};

// Lays out one node on screen. `type` may be null (a type no plugin provides): the node then
// shows the ports its links name.
NodeLayout layout_node(const std::string& id, const Node& node, const NodeType* type,
                       Position position, const CanvasView& view, Vec2 origin);

// Lays out a collapsed group as one node: its ports are the inner nodes' (group_ports).
NodeLayout layout_group(const Graph& graph, const Registry& registry, const Group& group,
                        const CanvasView& view, Vec2 origin);

// Lays out every node, a collapsed group as one node in place of its members; nodes without a saved
// position are placed in a column by topological depth so a graph written by hand still opens tidy.
std::vector<NodeLayout> layout_graph(const Graph& graph, const Registry& registry,
                                     const CanvasView& view, Vec2 origin);

// The position a node is drawn at (saved, or the automatic one).
Position node_position(const Graph& graph, const std::string& id);

// The position of a node, or of a collapsed group by its group_item_id.
Position item_position(const Graph& graph, const std::string& id);

// Canvas-unit bounds of all nodes (empty graph: a unit box at the origin).
Rect graph_bounds(const Graph& graph, const Registry& registry);
// Canvas-unit rectangle of one node.
Rect node_rect(const Graph& graph, const Registry& registry, const std::string& id);
// Where a new node of `type` wanted at `at` goes: there, or moved down until it overlaps no
// other node (with a small gap).
Position free_spot(const Graph& graph, const Registry& registry, const std::string& type,
                   Position at);
// The offset, starting from `offset` and moved further down as needed, at which copies of the
// nodes `ids` land clear of every node of the graph (Ctrl+D: copies below the originals, but
// never on the nodes already below them).
Position clear_offset(const Graph& graph, const Registry& registry,
                      const std::vector<std::string>& ids, Position offset);

// Canvas text is drawn at kTextSize * zoom pixels from a font rasterised at one of
// kTextRasterSizes: the smallest at least that large, so glyphs are only ever shrunk, by less
// than the step between sizes, never magnified (magnified bitmaps blur, shrunk ones by a lot
// alias).
inline constexpr float kTextSize = 13.0f;
inline constexpr float kTextRasterSizes[] = {4,  5,  6,  7,  8,  9,  10, 11, 12, 13,
                                             14, 16, 18, 20, 23, 26, 29, 33, 37, 42};
float text_raster_size(float pixels);
// Node titles are drawn at least this large (clipped to the node), so a graph fitted whole
// keeps its labels; other canvas text vanishes below 4 pixels.
inline constexpr float kMinTitlePixels = 9.0f;
inline float title_pixels(float zoom) {
  return kTextSize * zoom > kMinTitlePixels ? kTextSize * zoom : kMinTitlePixels;
}

// What a marked node's tooltip says: each reason once, in the editor's terms (a validation fix
// written for the JSON file, such as `add "inputs": {...}`, becomes the canvas gesture), and
// the evaluation's error left out when validation already says why the input is missing.
std::vector<std::string> node_reasons(const std::vector<std::string>& problems,
                                      const std::string& evaluation_error);

// The reroute dot within `reach` of `screen`: the link it belongs to and its index.
struct RerouteHit {
  std::string node;
  std::string input;
  size_t index = 0;
};
std::optional<RerouteHit> reroute_at(const Graph& graph, const CanvasView& view, Vec2 origin,
                                     Vec2 screen, float reach);

// The link (target node, input) passing within `reach` of `screen` (through its reroute dots),
// if any.
struct LinkHit {
  std::string node;
  std::string input;
};
std::optional<LinkHit> link_at(const Graph& graph, const std::vector<NodeLayout>& layouts,
                               Vec2 screen, float reach, float zoom);
// The link's curve from an output to an input (the canvas draws the same one).
Vec2 link_point(Vec2 from, Vec2 to, float zoom, float t);

// The minimap: the graph bounds scaled into a corner box of the canvas, and the view's
// rectangle in it. A click at a minimap point centres the view there.
struct Minimap {
  Rect box;         // screen
  float scale = 1;  // minimap pixels per canvas unit
  Vec2 canvas_min;  // canvas point at box.min (after centring)
  Vec2 to_minimap(Vec2 canvas) const {
    return {box.min.x + (canvas.x - canvas_min.x) * scale,
            box.min.y + (canvas.y - canvas_min.y) * scale};
  }
  Vec2 to_canvas(Vec2 screen) const {
    return {canvas_min.x + (screen.x - box.min.x) / scale,
            canvas_min.y + (screen.y - box.min.y) / scale};
  }
};
Minimap minimap_for(Rect graph_bounds, Vec2 origin, Vec2 size);
// Pans `view` so the canvas point `canvas` sits at the centre of a canvas of `size`.
void centre_on(CanvasView& view, Vec2 canvas, Vec2 size);

struct PortHit {
  std::string node;  // the node whose port it is (inside a collapsed group: the inner node)
  PortSpot spot;
};
// The spot where node.port is drawn: on the node's layout, or on its collapsed group's.
const PortSpot* find_port_spot(const std::vector<NodeLayout>& layouts, const std::string& node,
                               const std::string& port, bool input);
// The layout a node is drawn in: its own, or its collapsed group's.
const NodeLayout* find_node_layout(const std::vector<NodeLayout>& layouts, const std::string& node);
// The port within reach of `screen` (radius grows a little for the mouse), if any.
std::optional<PortHit> port_at(const std::vector<NodeLayout>& layouts, Vec2 screen, float reach);
// The topmost node under `screen` (later in the list is on top).
std::optional<std::string> node_at(const std::vector<NodeLayout>& layouts, Vec2 screen);

}  // namespace aq::editor
