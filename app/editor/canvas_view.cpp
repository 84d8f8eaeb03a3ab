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

void CanvasView::zoom_to(Vec2 origin, Vec2 screen, float new_zoom) {
  zoom_at(origin, screen, new_zoom / zoom);
}

void CanvasView::fit(Rect bounds, Vec2 size, std::optional<Vec2> focus, float min_zoom) {
  constexpr float kMargin = 30.0f;
  float w = std::max(bounds.max.x - bounds.min.x, 1.0f);
  float h = std::max(bounds.max.y - bounds.min.y, 1.0f);
  float zx = (size.x - 2 * kMargin) / w;
  float zy = (size.y - 2 * kMargin) / h;
  zoom = std::clamp(std::min(zx, zy), min_zoom, 1.5f);
  // Centred along an axis that fits; from the left or top end along one that does not.
  auto place = [&](float extent, float screen, float low) {
    if (extent * zoom <= screen - 2 * kMargin) return (screen - extent * zoom) * 0.5f - low * zoom;
    return kMargin - low * zoom;
  };
  pan.x = place(w, size.x, bounds.min.x);
  pan.y = place(h, size.y, bounds.min.y);
  if (focus) {
    // Bring the focus point in if the end shown first leaves it out.
    Vec2 at{pan.x + focus->x * zoom, pan.y + focus->y * zoom};
    if (at.x > size.x - kMargin) pan.x -= at.x - (size.x - kMargin) + NodeMetrics::kWidth * zoom;
    if (at.y > size.y - kMargin) pan.y -= at.y - (size.y - kMargin) + 80.0f * zoom;
  }
}

NodeLayout layout_node(const std::string& id, const Node& node, const NodeType* type,
                       Position position, const CanvasView& view, Vec2 origin) {
  NodeLayout layout;
  layout.id = id;
  layout.position = position;
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
    layout.inputs.push_back(
        {id, inputs[i].name, true, inputs[i].type, {layout.rect.min.x, row_y(i)}});
  }
  for (size_t i = 0; i < outputs.size(); ++i) {
    layout.outputs.push_back(
        {id, outputs[i].name, false, outputs[i].type, {layout.rect.max.x, row_y(i)}});
  }
  return layout;
}

NodeLayout layout_group(const Graph& graph, const Registry& registry, const Group& group,
                        const CanvasView& view, Vec2 origin) {
  NodeLayout layout;
  layout.id = group_item_id(group.name);
  layout.group = true;
  layout.members = group.nodes;
  layout.position = group.position;
  const GroupPorts ports = group_ports(graph, registry, group);
  const size_t rows = std::max<size_t>(std::max(ports.inputs.size(), ports.outputs.size()), 1);
  const float width = NodeMetrics::kWidth + 60.0f;  // room for "node.port" labels
  const float height = NodeMetrics::kHeader + rows * NodeMetrics::kRow + NodeMetrics::kFooter;
  const Vec2 top_left = view.to_screen(origin, {group.position.x, group.position.y});
  layout.rect = {top_left, {top_left.x + width * view.zoom, top_left.y + height * view.zoom}};
  layout.header = {top_left, {layout.rect.max.x, top_left.y + NodeMetrics::kHeader * view.zoom}};
  auto row_y = [&](size_t i) {
    return top_left.y + (NodeMetrics::kHeader + (i + 0.5f) * NodeMetrics::kRow) * view.zoom;
  };
  for (size_t i = 0; i < ports.inputs.size(); ++i) {
    const GroupPort& port = ports.inputs[i];
    layout.inputs.push_back(
        {port.inner.node, port.inner.port, true, port.type, {layout.rect.min.x, row_y(i)}});
  }
  for (size_t i = 0; i < ports.outputs.size(); ++i) {
    const GroupPort& port = ports.outputs[i];
    layout.outputs.push_back(
        {port.inner.node, port.inner.port, false, port.type, {layout.rect.max.x, row_y(i)}});
  }
  return layout;
}

const PortSpot* find_port_spot(const std::vector<NodeLayout>& layouts, const std::string& node,
                               const std::string& port, bool input) {
  for (const auto& layout : layouts) {
    for (const auto& spot : input ? layout.inputs : layout.outputs) {
      if (spot.node == node && spot.port == port) return &spot;
    }
  }
  return nullptr;
}

const NodeLayout* find_node_layout(const std::vector<NodeLayout>& layouts,
                                   const std::string& node) {
  for (const auto& layout : layouts) {
    if (layout.id == node ||
        std::find(layout.members.begin(), layout.members.end(), node) != layout.members.end()) {
      return &layout;
    }
  }
  return nullptr;
}

Position node_position(const Graph& graph, const std::string& id) {
  if (auto saved = read_position(graph, id)) return *saved;
  auto automatic = automatic_positions(graph);
  auto it = automatic.find(id);
  return it != automatic.end() ? it->second : Position{};
}

Position item_position(const Graph& graph, const std::string& id) {
  if (auto name = group_name_of_item(id)) {
    for (const auto& group : read_groups(graph)) {
      if (group.name == *name) return group.position;
    }
  }
  return node_position(graph, id);
}

std::vector<NodeLayout> layout_graph(const Graph& graph, const Registry& registry,
                                     const CanvasView& view, Vec2 origin) {
  std::map<std::string, Position> automatic;
  bool all_placed = std::all_of(graph.nodes.begin(), graph.nodes.end(), [&](const auto& entry) {
    return read_position(graph, entry.first).has_value();
  });
  if (!all_placed) automatic = automatic_positions(graph, &registry);
  std::vector<NodeLayout> out;
  out.reserve(graph.nodes.size());
  const std::vector<Group> groups = read_groups(graph);
  for (const auto& [id, node] : graph.nodes) {
    if (collapsed_group_of(groups, id) != nullptr) continue;  // drawn as its group
    Position at = read_position(graph, id).value_or(automatic[id]);
    out.push_back(layout_node(id, node, registry.find(node.type), at, view, origin));
  }
  for (const auto& group : groups) {
    if (group.collapsed) out.push_back(layout_group(graph, registry, group, view, origin));
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

Rect node_rect(const Graph& graph, const Registry& registry, const std::string& id) {
  CanvasView identity;
  identity.pan = {0, 0};
  identity.zoom = 1.0f;
  auto node = graph.nodes.find(id);
  if (node == graph.nodes.end()) return {};
  return layout_node(id, node->second, registry.find(node->second.type), node_position(graph, id),
                     identity, {0, 0})
      .rect;
}

Position free_spot(const Graph& graph, const Registry& registry, const std::string& type,
                   Position at) {
  constexpr float kGap = 20.0f;
  CanvasView identity;
  identity.pan = {0, 0};
  identity.zoom = 1.0f;
  const Node probe{type, {}, {}};
  std::vector<Rect> others;
  for (const auto& layout : layout_graph(graph, registry, identity, {0, 0})) {
    others.push_back(layout.rect);
  }
  for (int attempt = 0; attempt < 1000; ++attempt) {
    Rect rect = layout_node("", probe, registry.find(type), at, identity, {0, 0}).rect;
    Rect padded{{rect.min.x - kGap, rect.min.y - kGap}, {rect.max.x + kGap, rect.max.y + kGap}};
    const Rect* hit = nullptr;
    for (const auto& other : others) {
      if (padded.overlaps(other)) hit = &other;
    }
    if (hit == nullptr) return at;
    at.y = hit->max.y + kGap + 1.0f;
  }
  return at;
}

Position clear_offset(const Graph& graph, const Registry& registry,
                      const std::vector<std::string>& ids, Position offset) {
  constexpr float kGap = 20.0f;
  CanvasView identity;
  identity.pan = {0, 0};
  identity.zoom = 1.0f;
  std::vector<Rect> others;
  for (const auto& layout : layout_graph(graph, registry, identity, {0, 0})) {
    others.push_back(layout.rect);
  }
  std::vector<Rect> moving;
  for (const auto& id : ids) {
    if (graph.nodes.count(id)) moving.push_back(node_rect(graph, registry, id));
  }
  for (int attempt = 0; attempt < 1000; ++attempt) {
    float lowest_hit = -1e30f;
    for (const Rect& rect : moving) {
      Rect padded{{rect.min.x + offset.x - kGap, rect.min.y + offset.y - kGap},
                  {rect.max.x + offset.x + kGap, rect.max.y + offset.y + kGap}};
      for (const Rect& other : others) {
        if (padded.overlaps(other)) {
          // Move down so that this copy's top clears the node it hit.
          lowest_hit = std::max(lowest_hit, other.max.y + kGap + 1.0f - rect.min.y);
        }
      }
    }
    if (lowest_hit <= -1e29f) return offset;
    offset.y = std::max(offset.y + 1.0f, lowest_hit);
  }
  return offset;
}

float text_raster_size(float pixels) {
  for (float size : kTextRasterSizes) {
    if (size >= pixels) return size;
  }
  return kTextRasterSizes[std::size(kTextRasterSizes) - 1];
}

std::vector<std::string> node_reasons(const std::vector<std::string>& problems,
                                      const std::string& evaluation_error) {
  std::vector<std::string> reasons;
  auto add = [&](std::string reason) {
    const size_t json_fix = reason.find(": add \"inputs\"");
    if (json_fix != std::string::npos) {
      reason = reason.substr(0, json_fix) + ": drag a link from an output port onto it";
    }
    if (!reason.empty() && std::find(reasons.begin(), reasons.end(), reason) == reasons.end()) {
      reasons.push_back(reason);
    }
  };
  bool input_missing = false;
  for (const auto& problem : problems) {
    add(problem);
    input_missing = input_missing || problem.find("is not connected") != std::string::npos;
  }
  if (!(input_missing && evaluation_error.find("is not connected") != std::string::npos)) {
    add(evaluation_error);
  }
  return reasons;
}

Vec2 link_point(Vec2 from, Vec2 to, float zoom, float t) {
  // The cubic Bézier the canvas draws: tangents along x, half the span long.
  const float dx = std::max(std::fabs(to.x - from.x) * 0.5f, 30.0f * zoom);
  const Vec2 c1{from.x + dx, from.y};
  const Vec2 c2{to.x - dx, to.y};
  const float u = 1.0f - t;
  const float a = u * u * u, b = 3 * u * u * t, c = 3 * u * t * t, d = t * t * t;
  return {a * from.x + b * c1.x + c * c2.x + d * to.x, a * from.y + b * c1.y + c * c2.y + d * to.y};
}

std::optional<LinkHit> link_at(const Graph& graph, const std::vector<NodeLayout>& layouts,
                               Vec2 screen, float reach, float zoom) {
  for (const auto& [id, node] : graph.nodes) {
    const NodeLayout* target = find_node_layout(layouts, id);
    for (const auto& [input, source] : node.inputs) {
      if (target == nullptr) continue;
      const PortSpot* out = find_port_spot(layouts, source.node, source.port, false);
      const PortSpot* in = find_port_spot(layouts, id, input, true);
      if (out == nullptr || in == nullptr) continue;
      // The curve runs through the reroute dots; their screen places follow from the ports'.
      std::vector<Vec2> points = {out->at};
      const Vec2 origin{target->rect.min.x - target->position.x * zoom,
                        target->rect.min.y - target->position.y * zoom};
      for (const Position& dot : read_reroutes(graph, id, input)) {
        points.push_back({origin.x + dot.x * zoom, origin.y + dot.y * zoom});
      }
      points.push_back(in->at);
      for (size_t segment = 0; segment + 1 < points.size(); ++segment) {
        for (int i = 0; i <= 32; ++i) {
          Vec2 p = link_point(points[segment], points[segment + 1], zoom, i / 32.0f);
          if (std::hypot(p.x - screen.x, p.y - screen.y) <= reach) return LinkHit{id, input};
        }
      }
    }
  }
  return std::nullopt;
}

std::optional<RerouteHit> reroute_at(const Graph& graph, const CanvasView& view, Vec2 origin,
                                     Vec2 screen, float reach) {
  for (const auto& [id, node] : graph.nodes) {
    for (const auto& [input, source] : node.inputs) {
      const auto dots = read_reroutes(graph, id, input);
      for (size_t i = 0; i < dots.size(); ++i) {
        Vec2 at = view.to_screen(origin, {dots[i].x, dots[i].y});
        if (std::hypot(at.x - screen.x, at.y - screen.y) <= reach) return RerouteHit{id, input, i};
      }
    }
  }
  return std::nullopt;
}

Minimap minimap_for(Rect bounds, Vec2 origin, Vec2 size) {
  constexpr float kWidth = 180.0f;
  constexpr float kMargin = 10.0f;
  Minimap map;
  const float w = std::max(bounds.max.x - bounds.min.x, 1.0f);
  const float h = std::max(bounds.max.y - bounds.min.y, 1.0f);
  const float box_w = std::min(kWidth, size.x * 0.3f);
  const float box_h = std::min(box_w * 0.6f, size.y * 0.3f);
  map.box = {{origin.x + size.x - box_w - kMargin, origin.y + size.y - box_h - kMargin},
             {origin.x + size.x - kMargin, origin.y + size.y - kMargin}};
  map.scale = std::min((box_w - 8.0f) / w, (box_h - 8.0f) / h);
  // Centre the graph in the box.
  map.canvas_min = {bounds.min.x - ((box_w / map.scale) - w) * 0.5f,
                    bounds.min.y - ((box_h / map.scale) - h) * 0.5f};
  return map;
}

void centre_on(CanvasView& view, Vec2 canvas, Vec2 size) {
  view.pan.x = size.x * 0.5f - canvas.x * view.zoom;
  view.pan.y = size.y * 0.5f - canvas.y * view.zoom;
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
          best = PortHit{spot.node, spot};
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
