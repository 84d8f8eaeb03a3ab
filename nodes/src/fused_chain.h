// Pointwise fusion at execution time: the nodes the plan defers (PlannedNode::deferred) do not
// run; each keeps its call (parameters, inputs, context) as a stage of a FusedChain that the node
// reading it carries on, until a node that is not deferred runs the whole chain as one pass
// (pointwise_fusion.h), or as the epilogue of its producer's last draw (AQ_NODE_EPILOGUE).
//
//   deferred a ─┐ stage          deferred b ─┐ stage        c (not deferred)
//   [producer p]┴──────────────> chain ──────┴───────────> chain: one pass = p? ∘ a ∘ b ∘ c
#pragma once

#include <aquarelle/core/plan.h>
#include <aquarelle/core/registry.h>
#include <aquarelle/core/result.h>
#include <aquarelle/plugin.h>
#include <aquarelle/sdk/region.hpp>

#include <memory>
#include <string>
#include <vector>

#include "host_services.h"
#include "node_call.h"
#include "pointwise_fusion.h"

namespace aq {

// A node's call, kept until its chain's pass runs: the parameters and context its process()
// would have seen. The vectors own what `ctx` points into.
struct KeptCall {
  const NodeType* type = nullptr;
  std::vector<aq_param_value> params;
  std::vector<std::string> strings;  // params[i].s points into these
  std::vector<aq_input_value> inputs;
  std::vector<TextureRef> input_refs;  // held: extra inputs are read when the chain runs
  std::vector<uint64_t> input_keys;
  std::vector<DamageSource> sources;
  CallState call;
  aq_process_ctx ctx{};
};

// The deferred stages of a fused chain of pointwise nodes, kept until the node that ends the
// chain runs them in one pass (pointwise_fusion.h).
struct FusedChain {
  struct Stage : KeptCall {
    void* instance = nullptr;
  };
  // An epilogue producer (PlannedNode::producer): the node whose process() the chain's pass
  // runs, applying the stages in its last draw, instead of reading `input`.
  struct Producer : KeptCall {
    NodeState* state = nullptr;
    std::vector<std::vector<aq_input_value>> links;
    std::vector<aq_input_list> lists;
  };
  TextureRef input;  // the image the first stage reads
  std::unique_ptr<Producer> producer;
  std::vector<std::unique_ptr<Stage>> stages;
};

// Creates the node's plugin instance if it has none yet (built-in nodes have none).
Status ensure_instance(const std::string& id, const NodeType& type, NodeState& state,
                       const aq_host* host);

// A new chain whose pass runs `state`'s node (an epilogue producer) with `call`.
Result<std::shared_ptr<FusedChain>> start_producer_chain(const PlannedNode& planned,
                                                         NodeState& state, NodeCall&& call,
                                                         const FrameConstants& frame,
                                                         HostServices& host);

// Adds the node as the next stage of `chain`, starting a chain that reads the node's first
// input when `chain` is null.
Status append_stage(std::shared_ptr<FusedChain>& chain, const PlannedNode& planned,
                    NodeState& state, NodeCall&& call, const FrameConstants& frame,
                    HostServices& host);

// The format a fused pass writes a chain's result in: 8-bit HDR where the plan stores the chain's
// last node's output so for readers that decode it (the fused pass encodes), else `working`.
uint32_t chain_result_format(const std::vector<uint32_t>& stored, uint32_t working);

// Where a fused chain's stages may change its result through their other inputs (each read
// within the stage's reach, aq_pointwise_desc::reach) or their own parameters: what the
// producer must redraw besides its own damage (aq_host::epilogue_damage).
Region epilogue_damage_of(const FusedChain& chain, int width, int height);

// Runs the chain as one pass: the producer's process() with the stages as its epilogue, or the
// fused shader over chain.input at width x height. The result is stored as `planned` says.
Result<TextureRef> run_fused_pass(FusedChain& chain, const PlannedNode& planned, uint32_t format,
                                  int width, int height, PointwiseFuser& fuser, HostServices& host);

// What the stages' calls reported, one line per node ("node 'x' (type): ..."); empty if nothing.
std::string stage_errors(const FusedChain& chain);

// After a successful pass: what each stage and the producer saw, and where the chain's result
// (`state`'s output 0, under `previous_key` before) changed.
void finish_chain_damage(FusedChain& chain, NodeState& state, uint64_t previous_key);

}  // namespace aq
