// The error column of the bench's node table: each node of the timed graph that runs an
// approximation, its output against the same node at its exact setting, fed the same inputs
// (the rest of the graph as it is), so the column shows what that node's shortcut costs.
//
// A node type that trades accuracy for time adds one row to kExactSettings
// (bench_node_error.cpp): the parameter values at which it computes its definition.
#pragma once

#include <aquarelle/core/gl_context.h>
#include <aquarelle/core/graph.h>
#include <aquarelle/core/registry.h>
#include <aquarelle/core/result.h>

#include <nlohmann/json.hpp>

#include <map>
#include <string>

#include "bench_measure.h"

namespace aq::app {

// The parameter values that make a node of `type` exact, e.g. {"resolution": 1}; null when the
// type has no approximation the bench knows of.
nlohmann::json exact_setting(const std::string& type);

struct NodeError {
  std::string against;  // the exact setting in words, e.g. "resolution=1"
  bool exact = false;   // the node already runs at its exact setting (error 0, not measured)
  ErrorStats error;     // its output against the exact node's (colour channels)
  // What the reader must know: the outputs' sizes differed (the node's output was resampled to
  // the exact one's), or why no error could be measured (then error holds NaN).
  std::string note;
};

// For every node of `graph` with an exact setting: evaluates the graph at the node's first
// output as it is and with that node alone at its exact setting, at the graph's size, quality
// and first frame, and compares the two. Keyed by node id. A node whose error cannot be measured
// (its exact setting fails to run) gets a note and NaN, never failing the bench.
std::map<std::string, NodeError> node_errors(GlContext& context, const Registry& registry,
                                             const Graph& graph);

}  // namespace aq::app
