// Bypass ("bypass": true on a node in the graph file, Nuke's disable): the node passes its
// input through unchanged. It is a rewrite of the graph before planning, so the planner and
// the executor never see a bypassed node: every link from a bypassed node's output goes to the
// source of that node's first input of the same port type (image to image, scene to scene),
// following a chain of bypassed nodes. The image that arrives is the input's own, so its
// size and format are unchanged.
//
// A bypassed node that has no such input linked (a source such as `noise` or `scene`, or a
// filter whose input is not linked) has nothing to pass through: reading its output is an error
// naming the node, which asks to enable or remove it. It is not turned into a black image,
// because a silent black frame in a render is worse than a refusal that says why.
#pragma once

#include <aquarelle/core/graph.h>
#include <aquarelle/core/registry.h>
#include <aquarelle/core/result.h>

#include <optional>
#include <string>
#include <utility>

namespace aq {

// True when some node of the graph is bypassed.
bool has_bypassed_nodes(const Graph& graph);

// Where the output `ref` really comes from: `ref` itself unless its node is bypassed, else the
// source it passes through; an error naming the node when it has nothing to pass through.
Result<PortRef> bypass_source(const Graph& graph, const Registry& registry, const PortRef& ref);

// The graph with every read of a bypassed node's output redirected as described above
// (bypassed nodes stay in the graph, read by nobody). Fails when a bypassed node that is read
// has nothing to pass through.
Result<Graph> apply_bypass(const Graph& graph, const Registry& registry);

// What the evaluator plans and runs: the given graph itself when no node is bypassed (no copy:
// the case of nearly every frame), else apply_bypass's rewrite; and the requested output (a
// bypassed node's, when the editor views one) redirected the same way.
struct BypassedGraph {
  std::optional<Graph> rewritten;
  std::optional<PortRef> output;
  const Graph& graph(const Graph& given) const { return rewritten ? *rewritten : given; }
};
Result<BypassedGraph> bypassed_graph(const Graph& graph, const Registry& registry,
                                     const std::optional<PortRef>& requested);

}  // namespace aq
