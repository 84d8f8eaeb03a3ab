// The canvas's geometry without a window: zoom keeps the point under the mouse still, fit
// frames every node, ports are hit where they are drawn, unplaced nodes are laid out left to
// right by their depth in the graph.
//
// The test executables link only the test support library: the editor files under test are
// compiled in here (they need the core library alone).
#include "editor/canvas_view.h"
#include "editor/document.h"

#include <gtest/gtest.h>

namespace aq::editor {
namespace {

Registry make_registry() {
  Registry registry;
  std::string why;
  NodeType source;
  source.name = "source";
  PortInfo image;
  image.name = "image";
  source.outputs = {image};
  EXPECT_TRUE(registry.add(source, &why)) << why;
  NodeType filter;
  filter.name = "filter";
  PortInfo depth;
  depth.name = "depth";
  filter.inputs = {image, depth};
  filter.outputs = {image};
  EXPECT_TRUE(registry.add(filter, &why)) << why;
  return registry;
}

TEST(CanvasView, ZoomKeepsThePointUnderTheMouse) {
  CanvasView view;
  const Vec2 origin{100, 50};
  const Vec2 mouse{420, 310};
  const Vec2 before = view.to_canvas(origin, mouse);
  view.zoom_at(origin, mouse, 1.7f);
  EXPECT_FLOAT_EQ(view.zoom, 1.7f);
  const Vec2 after = view.to_canvas(origin, mouse);
  EXPECT_NEAR(after.x, before.x, 1e-3);
  EXPECT_NEAR(after.y, before.y, 1e-3);
  // Round trip canvas → screen → canvas.
  Vec2 screen = view.to_screen(origin, {12.5f, -40.0f});
  Vec2 back = view.to_canvas(origin, screen);
  EXPECT_NEAR(back.x, 12.5f, 1e-3);
  EXPECT_NEAR(back.y, -40.0f, 1e-3);
  // Zoom stays within its limits however far the wheel turns.
  for (int i = 0; i < 50; ++i) view.zoom_at(origin, mouse, 2.0f);
  EXPECT_FLOAT_EQ(view.zoom, CanvasView::kMaxZoom);
  for (int i = 0; i < 50; ++i) view.zoom_at(origin, mouse, 0.5f);
  EXPECT_FLOAT_EQ(view.zoom, CanvasView::kMinZoom);
}

TEST(CanvasView, FitFramesTheBounds) {
  CanvasView view;
  const Rect bounds{{-300, 100}, {900, 700}};
  const Vec2 size{800, 600};
  // The whole graph, however small (View > Show whole graph); F alone stops at a readable zoom.
  view.fit(bounds, size, std::nullopt, CanvasView::kMinZoom);
  Vec2 lo = view.to_screen({0, 0}, bounds.min);
  Vec2 hi = view.to_screen({0, 0}, bounds.max);
  EXPECT_GE(lo.x, 0.0f);
  EXPECT_GE(lo.y, 0.0f);
  EXPECT_LE(hi.x, size.x);
  EXPECT_LE(hi.y, size.y);
  // Centred, and the wider side nearly fills the view.
  EXPECT_NEAR((lo.x + hi.x) * 0.5f, size.x * 0.5f, 1.0f);
  EXPECT_NEAR((lo.y + hi.y) * 0.5f, size.y * 0.5f, 1.0f);
  EXPECT_GT(hi.x - lo.x, size.x * 0.8f);
}

TEST(CanvasView, PortsAreHitWhereTheyAreDrawnAtAnyZoom) {
  Registry registry = make_registry();
  Graph graph;
  graph.nodes["a"] = Node{"source", {}, {}};
  graph.nodes["b"] = Node{"filter", {}, {{"image", PortRef{"a", "image"}}}};
  write_position(graph, "a", Position{0, 0});
  write_position(graph, "b", Position{300, 0});
  for (float zoom : {0.3f, 1.0f, 2.5f}) {
    CanvasView view;
    view.zoom = zoom;
    view.pan = {17, 23};
    const Vec2 origin{5, 7};
    auto layouts = layout_graph(graph, registry, view, origin);
    ASSERT_EQ(layouts.size(), 2u);
    const NodeLayout& b = layouts[1];
    ASSERT_EQ(b.id, "b");
    ASSERT_EQ(b.inputs.size(), 2u);
    // The node's corner sits at its saved position.
    Vec2 corner = view.to_screen(origin, {300, 0});
    EXPECT_FLOAT_EQ(b.rect.min.x, corner.x);
    EXPECT_FLOAT_EQ(b.rect.min.y, corner.y);
    EXPECT_NEAR(b.rect.max.x - b.rect.min.x, NodeMetrics::kWidth * zoom, 1e-3);
    // Each port is found at its own spot, and not at its neighbour's.
    for (const auto& spot : b.inputs) {
      auto hit = port_at(layouts, spot.at, 4.0f);
      ASSERT_TRUE(hit.has_value());
      EXPECT_EQ(hit->node, "b");
      EXPECT_EQ(hit->spot.port, spot.port);
      EXPECT_TRUE(hit->spot.is_input);
    }
    auto out = port_at(layouts, layouts[0].outputs[0].at, 4.0f);
    ASSERT_TRUE(out.has_value());
    EXPECT_EQ(out->node, "a");
    EXPECT_FALSE(out->spot.is_input);
    // Away from every port: nothing; inside a node's body: that node.
    EXPECT_FALSE(port_at(layouts, {b.rect.min.x + 40 * zoom, b.rect.min.y + 5}, 4.0f));
    EXPECT_EQ(node_at(layouts, {b.rect.min.x + 40 * zoom, b.rect.min.y + 5}), "b");
    EXPECT_FALSE(node_at(layouts, {b.rect.max.x + 50, b.rect.max.y + 50}));
  }
}

TEST(CanvasView, UnplacedNodesFlowLeftToRightAndGetSavedPositions) {
  Registry registry = make_registry();
  Graph graph;
  graph.nodes["c"] = Node{"filter", {}, {{"image", PortRef{"b", "image"}}}};
  graph.nodes["b"] = Node{"filter", {}, {{"image", PortRef{"a", "image"}}}};
  graph.nodes["a"] = Node{"source", {}, {}};
  graph.nodes["d"] = Node{"source", {}, {}};
  auto automatic = automatic_positions(graph);
  EXPECT_LT(automatic["a"].x, automatic["b"].x);
  EXPECT_LT(automatic["b"].x, automatic["c"].x);
  EXPECT_EQ(automatic["a"].x, automatic["d"].x);
  EXPECT_NE(automatic["a"].y, automatic["d"].y);  // same column, different rows
  write_position(graph, "b", Position{1000, 1000});
  place_unplaced_nodes(graph);
  EXPECT_EQ(read_position(graph, "b"), (Position{1000, 1000}));  // a saved position stays
  EXPECT_EQ(read_position(graph, "c"), automatic["c"]);
  EXPECT_TRUE(read_position(graph, "a").has_value());
  Rect bounds = graph_bounds(graph, registry);
  EXPECT_LE(bounds.min.x, 0.0f);
  EXPECT_GE(bounds.max.x, 1000.0f + NodeMetrics::kWidth);
}

TEST(CanvasView, FitStaysReadableAndShowsTheStartOfAWideGraph) {
  // Fifteen nodes in a row, like the flagship graph: fitting all of them into 700 pixels
  // would shrink the text to nothing.
  const Rect wide{{0, 0}, {15 * 200.0f, 120}};
  CanvasView view;
  view.fit(wide, {700, 500});
  EXPECT_GE(view.zoom, CanvasView::kReadableZoom);
  EXPECT_GE(kTextSize * view.zoom, 9.0f) << "node text at least 9 px";
  // The left end of the graph is on screen; the rest is a pan away.
  Vec2 start = view.to_screen({0, 0}, wide.min);
  EXPECT_GE(start.x, 0.0f);
  EXPECT_LT(start.x, 100.0f);
  // A focus point (the output node at the right end) is brought into view.
  view.fit(wide, {700, 500}, Vec2{2800, 0});
  Vec2 focus = view.to_screen({0, 0}, {2800, 0});
  EXPECT_GE(focus.x, 0.0f);
  EXPECT_LE(focus.x + NodeMetrics::kWidth * view.zoom, 700.0f);
  // A small graph is still centred and may be magnified.
  view.fit({{0, 0}, {200, 100}}, {700, 500});
  Vec2 centre = view.to_screen({0, 0}, {100, 50});
  EXPECT_NEAR(centre.x, 350.0f, 1.0f);
  EXPECT_NEAR(centre.y, 250.0f, 1.0f);
}

TEST(CanvasView, ZoomOneToOneKeepsThePointUnderTheCursor) {
  CanvasView view;
  view.zoom = 0.45f;
  view.pan = {-300, 80};
  const Vec2 origin{10, 30};
  const Vec2 cursor{512, 300};
  const Vec2 before = view.to_canvas(origin, cursor);
  view.zoom_to(origin, cursor, 1.0f);
  EXPECT_FLOAT_EQ(view.zoom, 1.0f);
  const Vec2 after = view.to_canvas(origin, cursor);
  EXPECT_NEAR(after.x, before.x, 1e-3f);
  EXPECT_NEAR(after.y, before.y, 1e-3f);
}

TEST(CanvasView, TextIsRasterisedNearTheSizeItIsDrawnAt) {
  // Every zoom draws text from a font rasterised at most one step larger, never smaller
  // (a magnified bitmap font is what garbled "light" into "'ight").
  for (float zoom = CanvasView::kMinZoom; zoom <= CanvasView::kMaxZoom; zoom += 0.01f) {
    const float pixels = kTextSize * zoom;
    // Under 4 px text is not drawn at all; above the largest size it is shrunk from it.
    if (pixels < 4.0f || pixels > kTextRasterSizes[std::size(kTextRasterSizes) - 1]) continue;
    const float raster = text_raster_size(pixels);
    EXPECT_GE(raster, pixels) << "zoom " << zoom;
    EXPECT_LE(raster, std::max(pixels * 1.2f, pixels + 1.0f)) << "zoom " << zoom;
  }
}

TEST(CanvasView, NewNodesLandClearOfOthers) {
  Registry registry = make_registry();
  Graph graph;
  graph.nodes["a"] = Node{"source", {}, {}};
  graph.nodes["b"] = Node{"filter", {}, {{"image", PortRef{"a", "image"}}}};
  write_position(graph, "a", Position{0, 0});
  write_position(graph, "b", Position{0, 120});
  Position at = free_spot(graph, registry, "filter", {10, 10});
  graph.nodes["c"] = Node{"filter", {}, {}};
  write_position(graph, "c", at);
  Rect c = node_rect(graph, registry, "c");
  EXPECT_FALSE(c.overlaps(node_rect(graph, registry, "a")));
  EXPECT_FALSE(c.overlaps(node_rect(graph, registry, "b")));
  EXPECT_FLOAT_EQ(at.x, 10.0f) << "moved down only";
  // A free spot is kept as asked.
  EXPECT_EQ(free_spot(graph, registry, "filter", {600, 0}), (Position{600, 0}));
}

TEST(CanvasView, MinimapMapsTheGraphIntoItsBoxBothWays) {
  const Rect bounds{{-100, 0}, {2900, 400}};
  const Minimap map = minimap_for(bounds, {0, 0}, {800, 600});
  EXPECT_LE(map.box.max.x, 800.0f);
  EXPECT_LE(map.box.max.y, 600.0f);
  for (Vec2 corner : {bounds.min, bounds.max}) {
    Vec2 on_map = map.to_minimap(corner);
    EXPECT_TRUE(map.box.contains(on_map)) << on_map.x << ", " << on_map.y;
    Vec2 back = map.to_canvas(on_map);
    EXPECT_NEAR(back.x, corner.x, 0.01f);
    EXPECT_NEAR(back.y, corner.y, 0.01f);
  }
  CanvasView view;
  centre_on(view, {1400, 200}, {800, 600});
  Vec2 centre = view.to_screen({0, 0}, {1400, 200});
  EXPECT_NEAR(centre.x, 400.0f, 0.01f);
  EXPECT_NEAR(centre.y, 300.0f, 0.01f);
}

}  // namespace
}  // namespace aq::editor
