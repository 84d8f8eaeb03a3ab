// Canvas geometry: pan and zoom, node and port placement, hit testing. No ImGui here.
#include "canvas_view.h"

#include <algorithm>
#include <cmath>
#include <map>

namespace aq::editor {

namespace {}  // namespace

void CanvasView::zoom_at(Vec2 origin, Vec2 screen, float factor) {
  Vec2 anchor = to_canvas(origin, screen);
  zoom = std::clamp(zoom * factor, kMinZoom, kMaxZoom);
  pan.x = screen.x - origin.x - anchor.x * zoom;
  pan.y = screen.y - origin.y - anchor.y * zoom;
}

void CanvasView::fit(Rect bounds, Vec2 size) {
  constexpr float kMargin = 30.0f;
  float w = std::max(bounds.max.x - bounds.min.x, 1.0f);
  float h = std::max(bounds.max.y - bounds.min.y, 1.0f);
  float zx = (size.x - 2 * kMargin) / w;
  float zy = (size.y - 2 * kMargin) / h;
  zoom = std::clamp(std::min(zx, zy), kMinZoom, 1.5f);
  pan.x = (size.x - w * zoom) * 0.5f - bounds.min.x * zoom;
  pan.y = (size.y - h * zoom) * 0.5f - bounds.min.y * zoom;
}

NodeLayout layout_node(const std::string& id, const Node& node, const NodeType* type,
                       Position position, const CanvasView& view, Vec2 origin) {
  NodeLayout layout;
  layout.id = id;
  std::vector<PortInfo> inputs;
  std::vector<PortInfo> outputs;
  if (type != nullptr) {
    inputs = type->inputs;
    outputs = type->outputs;
  } else {
    for (const auto& [port, source] : node.inputs) {
      PortInfo info;
      info.name = port;
      inputs.push_back(info);
    }
  }
  size_t rows = std::max<size_t>(std::max(inputs.size(), outputs.size()), 1);
  float height = NodeMetrics::kHeader + rows * NodeMetrics::kRow + NodeMetrics::kFooter;
  Vec2 top_left = view.to_screen(origin, {position.x, position.y});
  layout.rect = {top_left,
                 {top_left.x + NodeMetrics::kWidth * view.zoom, top_left.y + height * view.zoom}};
  layout.header = {top_left, {layout.rect.max.x, top_left.y + NodeMetrics::kHeader * view.zoom}};
  auto row_y = [&](size_t i) {
    return top_left.y + (NodeMetrics::kHeader + (i + 0.5f) * NodeMetrics::kRow) * view.zoom;
  };
  for (size_t i = 0; i < inputs.size(); ++i) {
    layout.inputs.push_back({inputs[i].name, true, inputs[i].type, {layout.rect.min.x, row_y(i)}});
  }
  for (size_t i = 0; i < outputs.size(); ++i) {
    layout.outputs.push_back(
        {outputs[i].name, false, outputs[i].type, {layout.rect.max.x, row_y(i)}});
  }
  return layout;
}

Position node_position(const Graph& graph, const std::string& id) {
  if (auto saved = read_position(graph, id)) return *saved;
  auto automatic = automatic_positions(graph);
  auto it = automatic.find(id);
  return it != automatic.end() ? it->second : Position{};
}

std::vector<NodeLayout> layout_graph(const Graph& graph, const Registry& registry,
                                     const CanvasView& view, Vec2 origin) {
  std::map<std::string, Position> automatic;
  bool all_placed = std::all_of(graph.nodes.begin(), graph.nodes.end(), [&](const auto& entry) {
    return read_position(graph, entry.first).has_value();
  });
  if (!all_placed) automatic = automatic_positions(graph);
  std::vector<NodeLayout> out;
  out.reserve(graph.nodes.size());
  for (const auto& [id, node] : graph.nodes) {
    Position at = read_position(graph, id).value_or(automatic[id]);
    out.push_back(layout_node(id, node, registry.find(node.type), at, view, origin));
  }
  return out;
}

Rect graph_bounds(const Graph& graph, const Registry& registry) {
  if (graph.nodes.empty()) return {{0, 0}, {1, 1}};
  CanvasView identity;
  identity.pan = {0, 0};
  identity.zoom = 1.0f;
  Rect bounds{{1e30f, 1e30f}, {-1e30f, -1e30f}};
  for (const auto& layout : layout_graph(graph, registry, identity, {0, 0})) {
    bounds.min.x = std::min(bounds.min.x, layout.rect.min.x);
    bounds.min.y = std::min(bounds.min.y, layout.rect.min.y);
    bounds.max.x = std::max(bounds.max.x, layout.rect.max.x);
    bounds.max.y = std::max(bounds.max.y, layout.rect.max.y);
  }
  return bounds;
}

std::optional<PortHit> port_at(const std::vector<NodeLayout>& layouts, Vec2 screen, float reach) {
  std::optional<PortHit> best;
  float best_distance = reach * reach;
  for (const auto& layout : layouts) {
    for (const auto* spots : {&layout.inputs, &layout.outputs}) {
      for (const auto& spot : *spots) {
        float dx = spot.at.x - screen.x;
        float dy = spot.at.y - screen.y;
        float d = dx * dx + dy * dy;
        if (d <= best_distance) {
          best_distance = d;
          best = PortHit{layout.id, spot};
        }
      }
    }
  }
  return best;
}

std::optional<std::string> node_at(const std::vector<NodeLayout>& layouts, Vec2 screen) {
  for (auto it = layouts.rbegin(); it != layouts.rend(); ++it) {
    if (it->rect.contains(screen)) return it->id;
  }
  return std::nullopt;
}

}  // namespace aq::editor
