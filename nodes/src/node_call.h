// What one node is called with, and the key its result is cached under: its parameters as the ABI
// passes them, its inputs from the states of the nodes it reads, the process() context, and the
// cache key over all of it (evaluator.h: equal key, equal result). Each step is a plain function
// of the graph, the plan and the states, so it can be tested without running anything.
#pragma once

#include <aquarelle/core/evaluator.h>
#include <aquarelle/core/graph.h>
#include <aquarelle/core/plan.h>
#include <aquarelle/core/registry.h>
#include <aquarelle/core/result.h>
#include <aquarelle/plugin.h>

#include <cstdint>
#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include "host_services.h"

namespace aq {

// What every node of one evaluation shares: the graph's settings, the frame and the plan's sizes.
struct FrameConstants {
  const Settings* settings = nullptr;
  const EvalOptions* options = nullptr;
  const aq_host* host = nullptr;
  uint32_t gl_generation = 0;
  uint32_t format = 0;              // the plan's working format
  PixelSize working;                // the plan's working size
  double time = 0;                  // seconds since the graph's first frame
  std::filesystem::path graph_dir;  // relative path parameters resolve against it
};

// The constants for evaluating `graph` under `plan` at options.frame.
FrameConstants frame_constants(const Graph& graph, const Plan& plan, const EvalOptions& options,
                               const aq_host* host, uint32_t gl_generation);

// A node's parameters as the ABI passes them; `strings` owns what params[i].s points to.
struct ParamValues {
  std::vector<aq_param_value> params;
  std::vector<std::string> strings;
};

// Converts the node's parameters (defaults for missing ones) and hashes them into `key`.
ParamValues convert_params(const Node& node, const NodeType& type,
                           const std::filesystem::path& graph_dir, uint64_t* key);

// A node's inputs as the ABI passes them, and the textures behind its image inputs.
struct GatheredInputs {
  std::vector<aq_input_value> values;
  std::vector<uint64_t> keys;         // per input (aq_process_ctx::input_keys); 0 unconnected
  std::vector<TextureRef> images;     // per input; empty for scenes and unconnected inputs
  std::vector<DamageSource> sources;  // per input (aq_host::input_damage)
  // Every link of each input, for nodes with an AQ_PORT_MULTI port (ctx.input_lists); empty
  // otherwise. `lists` points into `links` (and into `values` for single-link inputs).
  std::vector<std::vector<aq_input_value>> links;
  std::vector<aq_input_list> lists;
};

// The one place that turns a node's links into its inputs (checking that each names an output
// of the right type) and hashes its sources' keys into `key`.
Result<GatheredInputs> gather_inputs(const std::string& id, const Node& node, const NodeType& type,
                                     std::map<std::string, NodeState>& states, uint64_t* key);

// Everything a node's run depends on: its parameters, its inputs and its keys.
struct NodeCall {
  ParamValues params;
  GatheredInputs inputs;
  uint64_t key = 0;       // the cache key: type, parameters, inputs' keys, frame settings
  uint64_t self_key = 0;  // the same without the inputs' keys (damage tracking)
  // The same without the frame: a time-dependent node's inputs' damage is relative to what it
  // read on its last call, whatever the frame (it adds what time changes itself).
  uint64_t damage_key = 0;
};

// The node's key and its inputs: converts its parameters, gathers its inputs from `states` and
// hashes both with what the frame adds (size, format, quality, the frame when time-dependent,
// the plan's storage choices). Errors name the node and the parameter or input.
Result<NodeCall> prepare_node_call(const PlannedNode& planned, const Node& node,
                                   const FrameConstants& frame,
                                   std::map<std::string, NodeState>& states);

// The context process() (or a fused stage's set_uniforms) sees for one node; `call` becomes its
// host_data. Input lists and keys are left null for the caller to point at what it keeps.
void fill_process_ctx(aq_process_ctx& ctx, const FrameConstants& frame, CallState& call,
                      std::vector<aq_input_value>& inputs, std::vector<aq_param_value>& params);

}  // namespace aq
