// The viewer's evaluation key and draft choice. See eval_policy.h.
#include "eval_policy.h"

#include <functional>
#include <vector>

namespace aq::editor {

std::set<std::string> upstream_nodes(const Graph& graph, const std::optional<PortRef>& output) {
  std::set<std::string> seen;
  if (!output) return seen;
  std::vector<std::string> todo = {output->node};
  while (!todo.empty()) {
    std::string id = todo.back();
    todo.pop_back();
    auto node = graph.nodes.find(id);
    if (node == graph.nodes.end() || !seen.insert(id).second) continue;
    for (const auto& [port, source] : node->second.inputs) todo.push_back(source.node);
  }
  return seen;
}

uint64_t evaluation_key(const Graph& graph, const std::optional<PortRef>& output) {
  nlohmann::json key = nlohmann::json::object();
  const Settings& s = graph.settings;
  key["settings"] = {s.width, s.height, s.fps, s.first_frame, s.last_frame, s.precision, s.quality};
  key["output"] = output ? output->str() : "";
  for (const auto& id : upstream_nodes(graph, output)) {
    const Node& node = graph.nodes.at(id);
    nlohmann::json& entry = key["nodes"][id];
    entry["type"] = node.type;
    if (node.bypass) entry["bypass"] = true;
    for (const auto& [name, value] : node.params) entry["params"][name] = value;
    for (const auto& [port, source] : node.inputs) entry["inputs"][port] = source.str();
  }
  return std::hash<std::string>{}(
      key.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace));
}

bool evaluate_as_draft(const DraftInputs& in) {
  if (in.graph_is_draft || in.last_full_ms <= 0) return false;
  if (in.playing) return in.last_full_ms > 1000.0 / (in.fps > 0 ? in.fps : 24.0);
  if (in.gesture) return in.last_full_ms > in.gesture_budget_ms;
  return false;
}

}  // namespace aq::editor

namespace aq::editor {

std::string proxy_quality(const DraftInputs& in) {
  if (!in.gesture && !in.playing) return "";  // idle: the full picture
  if (in.graph_is_draft || in.graph_quality == "draft") return "";
  if (in.graph_quality == "preview") return evaluate_as_draft(in) ? "draft" : "";
  // "final" (or a name the evaluator reads as final): in full while it keeps up (a fast graph
  // is never reduced), else the preview proxy, else draft.
  if (!evaluate_as_draft(in)) return "";
  const double budget = in.playing ? 1000.0 / (in.fps > 0 ? in.fps : 24.0) : in.gesture_budget_ms;
  return in.last_preview_ms > budget ? "draft" : "preview";
}

}  // namespace aq::editor
