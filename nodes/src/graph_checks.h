// Shared between reading (graph_read.cpp) and validating (graph_validate.cpp) graphs: the
// semantic checks of a graph model, and the helpers that name a problem's place by JSON
// pointer. Internal to the core library.
#pragma once

#include <aquarelle/core/graph_io.h>

#include <set>
#include <string>
#include <utility>
#include <vector>

namespace aq::graph_checks {

// What reading already reported from the JSON itself, so validation does not report the same
// thing twice (e.g. a malformed source is not also a "missing required input").
struct AlreadyReported {
  std::set<std::string> node_types;                      // node ids whose "type" was unusable
  std::set<std::pair<std::string, std::string>> inputs;  // (node id, port) with a bad source
  bool output = false;                                   // "output" present but unusable
};

std::vector<Problem> check_graph(const Graph& graph, const Registry& registry,
                                 const AlreadyReported& already_reported);

// A problem at `pointer`; the node id and the parameter, input or setting name are read from
// the pointer ("/nodes/blur/params/sigma" -> node "blur", field "sigma").
Problem problem_at(const std::string& pointer, std::string message);

std::string node_pointer(const std::string& node_id);
std::string param_pointer(const std::string& node_id, const std::string& param);
std::string input_pointer(const std::string& node_id, const std::string& port);

// "an integer", "a number", "a string", "a boolean", "an array", "an object" or "null".
std::string json_kind(const nlohmann::json& value);
// 'text', as names are quoted in messages.
std::string quoted(const std::string& text);

// "a, b, c" (or "(none)").
std::string join_names(const std::vector<std::string>& names);
// " (did you mean 'blur'?)" when one of `names` is a likely typo of `wanted`, else "".
std::string did_you_mean(const std::string& wanted, const std::vector<std::string>& names);

// Node ids: [A-Za-z_][A-Za-z0-9_-]* ('.' separates node and port in "node.port").
bool is_valid_node_id(const std::string& id);

}  // namespace aq::graph_checks
