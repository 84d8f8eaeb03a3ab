// The bench's per-node error against each node's exact setting (see bench_node_error.h).
#include "bench_node_error.h"

#include <aquarelle/core/evaluator.h>
#include <aquarelle/core/graph_io.h>

#include <limits>

namespace aq::app {

namespace {

using json = nlohmann::json;

struct ExactSetting {
  const char* type;
  const char* params;  // JSON object: the values at which the node computes its definition
};

// One row per node type with a shortcut; the README of each plugin states the maths.
const ExactSetting kExactSettings[] = {
    // Seed 002 (issue 35): passes on cells or rays per block, every pixel at resolution 1; the
    // clouds also against a fine-step march.
    {"bleed", R"({"resolution": 1})"},
    {"edge_darkening", R"({"resolution": 1})"},
    {"clouds", R"({"resolution": 1, "steps": 256})"},
    // Seed 001: the pipeline reference's settings (bench_graph_sweeps.cpp).
    {"blur", R"({"method": "gaussian", "linear_taps": false, "direct_kernel": "full"})"},
    {"caustics", R"({"grid": 1024, "auto_grid": false})"},
    {"shadowmap", R"({"size": 4096, "auto_size": false})"},
    // Seeds 003/004 (issue 36): the fast method's low-resolution lists against every layer at
    // full size (equal to reference::layered to the precision's rounding).
    {"layered", R"({"method": "exact"})"},
};

std::string in_words(const json& params) {
  std::string words;
  for (const auto& [name, value] : params.items()) {
    words += (words.empty() ? "" : ", ") + name + "=" +
             (value.is_string() ? value.get<std::string>() : value.dump());
  }
  return words;
}

// True when `node` already holds every value of `exact` (its own or the type's default).
bool already_exact(const Node& node, const NodeType& type, const json& exact) {
  for (const auto& [name, value] : exact.items()) {
    const ParamInfo* info = type.param(name);
    if (info == nullptr) return false;
    if (param_value_or_default(node, *info) != value) return false;
  }
  return true;
}

Result<ImageF> node_output(Evaluator& evaluator, const Graph& graph, const PortRef& port) {
  EvalOptions options;
  options.frame = graph.settings.first_frame;
  options.measure_gpu_time = false;
  auto texture = evaluator.evaluate(graph, options, port);
  if (!texture.ok()) return texture.error();
  return evaluator.read_back(*texture);
}

// The error of `id` at its settings against `exact` (both evaluated in `evaluator`).
Result<NodeError> measure_error(Evaluator& evaluator, const Graph& graph, const std::string& id,
                                const NodeType& type, const json& exact) {
  NodeError entry;
  entry.against = in_words(exact);
  const PortRef port{id, type.outputs.front().name};
  auto got = node_output(evaluator, graph, port);
  if (!got.ok()) return got.error();
  Graph exact_graph = graph;
  for (const auto& [name, value] : exact.items()) exact_graph.nodes[id].params[name] = value;
  auto want = node_output(evaluator, exact_graph, port);
  if (!want.ok()) return make_error("at " + entry.against + ": " + want.message());
  ImageF image = std::move(*got);
  if (image.width != want->width || image.height != want->height) {
    // A texture whose size is the setting (shadow map, caustic tile): compared as a shader
    // sampling it sees it, resampled to the exact one's size (the caustic tile wraps around).
    entry.note = "resampled from " + std::to_string(image.width) + "x" +
                 std::to_string(image.height) + " to the exact output's size";
    image = resample_bilinear(image, want->width, want->height, type.name == "caustics");
  }
  auto error = compare_images(image, *want);
  if (!error.ok()) return error.error();
  entry.error = *error;
  return entry;
}

}  // namespace

json exact_setting(const std::string& type) {
  for (const auto& row : kExactSettings) {
    if (type == row.type) return json::parse(row.params);
  }
  return nullptr;
}

std::map<std::string, NodeError> node_errors(GlContext& context, const Registry& registry,
                                             const Graph& graph) {
  std::map<std::string, NodeError> errors;
  Evaluator evaluator(context, registry);
  for (const auto& [id, node] : graph.nodes) {
    const json exact = exact_setting(node.type);
    const NodeType* type = registry.find(node.type);
    if (exact.is_null() || type == nullptr || type->outputs.empty()) continue;
    if (already_exact(node, *type, exact)) {
      NodeError entry;
      entry.against = in_words(exact);
      entry.exact = true;
      errors[id] = entry;
      continue;
    }
    auto measured = measure_error(evaluator, graph, id, *type, exact);
    if (measured.ok()) {
      errors[id] = *measured;
      continue;
    }
    NodeError failed;
    failed.against = in_words(exact);
    const double nan = std::numeric_limits<double>::quiet_NaN();
    failed.error = ErrorStats{nan, nan, nan};
    failed.note = "not measured: " + measured.message();
    errors[id] = failed;
  }
  return errors;
}

}  // namespace aq::app
