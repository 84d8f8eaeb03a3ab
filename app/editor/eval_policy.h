// When the viewer evaluates, and at which quality: pure functions of the graph and of timings,
// with no GL, so document tests can check them.
//
// The evaluation key covers what an image depends on: the nodes upstream of the viewed output
// (type, parameters, links) and the settings. The canvas layout (the graph's `editor` section)
// and nodes that do not feed the output are not part of it, so moving a node or adding an
// unconnected one does not re-evaluate.
#pragma once

#include <aquarelle/core/graph.h>

#include <cstdint>
#include <optional>
#include <set>
#include <string>

namespace aq::editor {

// The ids of the nodes `output` depends on (itself included); empty without an output.
std::set<std::string> upstream_nodes(const Graph& graph, const std::optional<PortRef>& output);

// A hash of what evaluating `output` of `graph` depends on (see above).
uint64_t evaluation_key(const Graph& graph, const std::optional<PortRef>& output);

// Draft (a quarter of the size, cheaper settings) only when a full evaluation cannot keep up
// with the interaction: during a continuous gesture (slider or node drag) when it takes longer
// than `gesture_budget_ms`, during playback when it takes longer than a frame of the graph's
// fps. A typed value, a link, an undo: always full. Unknown cost (no full evaluation yet): full.
constexpr double kGestureBudgetMs = 100.0;  // ten updates a second keep a drag responsive
struct DraftInputs {
  bool gesture = false;  // a slider drag or similar continuous edit is under way
  bool playing = false;
  double fps = 24.0;
  double last_full_ms = 0;      // the last evaluation at the graph's own quality; 0 = none yet
  bool graph_is_draft = false;  // the graph's own quality is "draft" already
  double gesture_budget_ms = kGestureBudgetMs;
  // The graph's own quality ("final" by default) and the last "preview" proxy's cost (0: none).
  std::string graph_quality = "final";
  double last_preview_ms = 0;
};
bool evaluate_as_draft(const DraftInputs& inputs);

// The quality the viewer evaluates at while the user drags a value or plays, as Nuke and
// Blender do: a graph at "final" quality whose full evaluation cannot keep up (see
// evaluate_as_draft) is shown as a "preview" proxy during the interaction ("draft" when even
// the preview cannot keep up), and in full once the user lets go; a "preview" graph drafts
// only when it cannot keep up. A graph that keeps up is never reduced. "" is the graph's own.
std::string proxy_quality(const DraftInputs& inputs);

}  // namespace aq::editor
