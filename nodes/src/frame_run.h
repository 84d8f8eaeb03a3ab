// One evaluation of a compiled plan, step by step. Evaluator::evaluate (evaluator.cpp) walks
// the plan's nodes in order and calls, for each one:
//
//   state_of        the node's state, kept between evaluations (outputs, instance, key)
//   prepare         the node's key and its inputs (node_call.h)
//   fuse            join the pointwise chain it reads, or start one (fused_chain.h)
//   defer | reuse | run_chain | run_node
//                   leave it to its reader's pass, keep its outputs (equal key), run its chain
//                   as one pass, or call its process(); each run records its timing
//   release_inputs  inputs read for the last time go back to the texture pool
//
// and output() at the end: the requested port, resampled to the graph's size after a proxy
// render.
#pragma once

#include <aquarelle/core/evaluator.h>
#include <aquarelle/core/graph.h>
#include <aquarelle/core/plan.h>
#include <aquarelle/core/result.h>

#include <chrono>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "fused_chain.h"
#include "host_services.h"
#include "node_call.h"
#include "pointwise_fusion.h"

namespace aq {

// Times one pass: wall time, and with options.measure_gpu_time a GL_TIMESTAMP pair;
// options.finish_each_node waits for the GPU on both ends so the wall time covers its work.
class PassClock {
 public:
  PassClock(NodeState& state, const EvalOptions& options);
  void stop();
  NodeTiming timing(const std::string& id, const NodeType& type) const;

 private:
  NodeState& state_;
  const EvalOptions& options_;
  std::chrono::steady_clock::time_point start_, end_;
};

// What one evaluation needs from the evaluator that outlives it.
struct EvaluatorParts {
  HostServices& host;
  PointwiseFuser& fuser;
  std::map<std::string, NodeState>& states;
  std::vector<NodeTiming>& timings;
  std::map<std::string, int>& run_counts;
};

class FrameRun {
 public:
  FrameRun(EvaluatorParts parts, const Graph& graph, const Plan& plan, const EvalOptions& options,
           uint32_t gl_generation);

  NodeState& state_of(const PlannedNode& planned);
  Result<NodeCall> prepare(const PlannedNode& planned);
  // The chain the node's pass runs (null: none), after the node joined or started it.
  Result<std::shared_ptr<FusedChain>> fuse(const PlannedNode& planned, NodeState& state,
                                           NodeCall& call);
  bool reusable(const NodeState& state, const NodeCall& call) const;

  Status defer(const PlannedNode& planned, NodeState& state, const NodeCall& call,
               std::shared_ptr<FusedChain> chain);
  Status reuse(const PlannedNode& planned);
  Status run_chain(const PlannedNode& planned, NodeState& state, const NodeCall& call,
                   FusedChain& chain);
  Status run_node(const PlannedNode& planned, NodeState& state, NodeCall& call);
  void release_inputs(const PlannedNode& planned);

  Result<TextureRef> output();

 private:
  bool keeps(const std::string& id) const;  // outputs stay after the last reader
  bool tail_into_resample(const PlannedNode& planned, const TextureRef& input) const;
  Status check_outputs(const PlannedNode& planned, NodeState& state, const CallState& call);
  Result<TextureRef> resample_output(const TextureRef& result);

  EvaluatorParts parts_;
  const Graph& graph_;
  const Plan& plan_;
  const EvalOptions& options_;
  FrameConstants frame_;
  std::map<std::string, int> readers_;  // readers left per node
  std::map<std::string, bool> varies_;
  // The stages of each fused chain so far, by the id of its last deferred node.
  std::map<std::string, std::shared_ptr<FusedChain>> chains_;
};

}  // namespace aq
