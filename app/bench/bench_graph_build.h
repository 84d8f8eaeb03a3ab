// Small helpers the sweeps of `aquarelle bench` share: a graph holding one node fed by
// `image_input` nodes, parameter values as the user's graph sets them, and the fixed test
// images the node sweeps run on.
#pragma once

#include <aquarelle/core/graph.h>
#include <aquarelle/core/image.h>
#include <aquarelle/core/registry.h>
#include <aquarelle/reference/caustics_reference.h>

#include <nlohmann/json.hpp>

#include <map>
#include <string>

namespace aq::app {

// The id of the node under test in single_node_graph().
inline constexpr const char* kNodeUnderTest = "node";

// A graph `node` of `type` with `params`; each entry of `inputs` (port -> image name) is fed by
// an `image_input` node of that name. Output: node's first output port.
Graph single_node_graph(const Registry& registry, const std::string& type,
                        const nlohmann::json& params,
                        const std::map<std::string, std::string>& inputs, int width, int height,
                        const std::string& precision);

// The value of `param` on the first node of `type` in `graph` (by id order), else the type's
// default; null when the type or parameter does not exist.
nlohmann::json graph_param(const Graph& graph, const Registry& registry, const std::string& type,
                           const std::string& param);

// Id of the first node of `type` in `graph` (by id order), empty when none.
std::string first_node_of_type(const Graph& graph, const std::string& type);

// A parameter value as a number, `fallback` when it is not one (absent, null).
double number(const nlohmann::json& value, double fallback);

// The caustics parameters of `graph` (its first `caustics` node, else the type's defaults) for
// the CPU reference at `resolution` texels.
reference::CausticsParams caustics_params_of(const Graph& graph, const Registry& registry,
                                             int resolution);

// The fixed colour test input: smooth gradients, hashed pixel noise and hard-edged squares, in
// [0, 1], deterministic.
ImageF sweep_test_image(int width, int height);

// A depth ramp for depth-dependent nodes: view depth 0.5 .. 40 from left to right, with a
// near square in the middle (channel 0; the rest copy it).
ImageF sweep_depth_image(int width, int height);

}  // namespace aq::app
