// Semantic checks of a graph model: settings in range, node ids well formed, node types
// installed, parameters of the right type and in range, inputs that exist and connect to an
// existing output of the same port type, required inputs connected, no cycles, a usable
// output. Every problem is collected (nothing stops at the first), each named by JSON pointer;
// reading adds line and column.
#include <aquarelle/core/bypass.h>
#include <aquarelle/core/graph_io.h>

#include <algorithm>
#include <cmath>
#include <set>
#include <sstream>
#include <unordered_map>

#include "graph_checks.h"
#include "json_locator.h"

namespace aq {
namespace graph_checks {
namespace {

constexpr int kMaxImageSize = 16384;

std::string number_text(double value) {
  std::ostringstream out;
  out.precision(17);
  out << value;
  return out.str();
}

// Edits (insert, delete, substitute, swap two neighbours) turning `a` into `b`: the optimal
// string alignment distance, so "dpeth" is one edit from "depth".
size_t edit_distance(const std::string& a, const std::string& b) {
  std::vector<std::vector<size_t>> d(a.size() + 1, std::vector<size_t>(b.size() + 1));
  for (size_t i = 0; i <= a.size(); ++i) d[i][0] = i;
  for (size_t j = 0; j <= b.size(); ++j) d[0][j] = j;
  for (size_t i = 1; i <= a.size(); ++i) {
    for (size_t j = 1; j <= b.size(); ++j) {
      const size_t cost = a[i - 1] == b[j - 1] ? 0 : 1;
      d[i][j] = std::min({d[i - 1][j] + 1, d[i][j - 1] + 1, d[i - 1][j - 1] + cost});
      if (i > 1 && j > 1 && a[i - 1] == b[j - 2] && a[i - 2] == b[j - 1]) {
        d[i][j] = std::min(d[i][j], d[i - 2][j - 2] + 1);
      }
    }
  }
  return d[a.size()][b.size()];
}

template <typename Info>
std::vector<std::string> names_of(const std::vector<Info>& items) {
  std::vector<std::string> names;
  for (const Info& item : items) names.push_back(item.name);
  return names;
}

std::string got(const nlohmann::json& value) {
  std::string text =
      value.is_structured()
          ? ""
          : " " + value.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace);
  if (text.size() > 40) text = text.substr(0, 37) + "...";
  return "got " + json_kind(value) + text;
}

std::string range_text(const ParamInfo& param) {
  return "[" + number_text(param.min_value) + ", " + number_text(param.max_value) + "]";
}

// Checks one number against the parameter's range; "" when fine.
std::string check_number(const ParamInfo& param, const nlohmann::json& value, bool integral,
                         const std::string& what) {
  if (!value.is_number()) {
    return "expected " + what + (integral ? " (an integer)" : " (a number)") + ", " + got(value);
  }
  const double number = value.get<double>();
  if (!std::isfinite(number)) return what + " must be a finite number";
  if (integral && std::floor(number) != number) {
    return "expected an integer, got " + number_text(number);
  }
  if (number < param.min_value || number > param.max_value) {
    return what + " " + number_text(number) + " is outside the range " + range_text(param);
  }
  return "";
}

std::string check_param_value(const ParamInfo& param, const nlohmann::json& value) {
  switch (param.type) {
    case AQ_PARAM_FLOAT:
      return check_number(param, value, false, "value");
    case AQ_PARAM_INT:
      return check_number(param, value, true, "value");
    case AQ_PARAM_BOOL:
      return value.is_boolean() ? "" : "expected true or false, " + got(value);
    case AQ_PARAM_ENUM: {
      const std::string choices = join_names(param.enum_values);
      if (!value.is_string()) return "expected one of " + choices + " (a string), " + got(value);
      const auto& name = value.get_ref<const std::string&>();
      if (std::find(param.enum_values.begin(), param.enum_values.end(), name) ==
          param.enum_values.end()) {
        return quoted(name) + " is not one of " + choices + did_you_mean(name, param.enum_values);
      }
      return "";
    }
    case AQ_PARAM_STRING:
    case AQ_PARAM_PATH:
      return value.is_string() ? "" : "expected a string, " + got(value);
    case AQ_PARAM_COLOR:
    case AQ_PARAM_VEC3: {
      const char* shape = param.type == AQ_PARAM_COLOR ? "[r, g, b]" : "[x, y, z]";
      if (!value.is_array() || value.size() != 3) {
        return std::string("expected an array of 3 numbers ") + shape + ", " + got(value) +
               (value.is_array() ? " of " + std::to_string(value.size()) + " elements" : "");
      }
      static const char* kComponents[2][3] = {{"r", "g", "b"}, {"x", "y", "z"}};
      const int row = param.type == AQ_PARAM_COLOR ? 0 : 1;
      for (int i = 0; i < 3; ++i) {
        const std::string component = std::string("component ") + kComponents[row][i];
        if (std::string why = check_number(param, value[i], false, component); !why.empty()) {
          return why;
        }
      }
      return "";
    }
  }
  return "parameter type " + std::to_string(param.type) + " is unknown to this build";
}

void check_settings(const Settings& settings, std::vector<Problem>* problems) {
  auto check_size = [&](int value, const char* key) {
    if (value < 1 || value > kMaxImageSize) {
      problems->push_back(problem_at(std::string("/settings/") + key,
                                     std::string(key) + " " + std::to_string(value) +
                                         " must be a whole number of pixels in 1.." +
                                         std::to_string(kMaxImageSize)));
    }
  };
  check_size(settings.width, "width");
  check_size(settings.height, "height");
  if (!(std::isfinite(settings.fps) && settings.fps > 0)) {
    problems->push_back(problem_at(
        "/settings/fps", "fps " + number_text(settings.fps) + " must be a positive number"));
  }
  if (std::string why = frame_range_problem(settings.first_frame, settings.last_frame);
      !why.empty()) {
    problems->push_back(
        problem_at("/settings/frames", "frames [" + std::to_string(settings.first_frame) + ", " +
                                           std::to_string(settings.last_frame) + "]: " + why));
  }
  if (settings.precision != "half" && settings.precision != "float") {
    problems->push_back(
        problem_at("/settings/precision",
                   "precision " + quoted(settings.precision) + " must be 'half' or 'float'"));
  }
  if (settings.quality != "draft" && settings.quality != "preview" && settings.quality != "final") {
    problems->push_back(problem_at(
        "/settings/quality",
        "quality " + quoted(settings.quality) + " must be 'draft', 'preview' or 'final'"));
  }
}

// `ids`: every node id of the graph, made once per graph (not per bad link: a graph with
// thousands of bad links would otherwise copy thousands of ids for each).
void check_node(const std::string& id, const Node& node, const Graph& graph,
                const std::vector<std::string>& ids, const Registry& registry,
                const AlreadyReported& already, std::vector<Problem>* problems) {
  if (!is_valid_node_id(id)) {
    problems->push_back(problem_at(
        node_pointer(id),
        "node id " + quoted(id) +
            " is not allowed: use letters, digits, '_' and '-', starting with a letter or '_' "
            "('.' separates node and port in \"node.port\")"));
  }
  const NodeType* type = registry.find(node.type);
  if (type == nullptr && already.node_types.count(id) == 0) {
    const std::vector<std::string> installed = registry.names();
    problems->push_back(
        problem_at(node_pointer(id) + "/type", "unknown node type " + quoted(node.type) +
                                                   did_you_mean(node.type, installed) +
                                                   "; installed types: " + join_names(installed)));
  }

  for (const auto& [name, value] : node.params) {
    if (type == nullptr) break;  // nothing to check the parameters against
    const ParamInfo* param = type->param(name);
    if (param == nullptr) {
      const std::vector<std::string> known = names_of(type->params);
      problems->push_back(problem_at(param_pointer(id, name),
                                     "unknown parameter " + quoted(name) + " of node type " +
                                         quoted(type->name) + did_you_mean(name, known) +
                                         "; its parameters: " + join_names(known)));
      continue;
    }
    if (std::string why = check_param_value(*param, value); !why.empty()) {
      problems->push_back(problem_at(param_pointer(id, name),
                                     std::string(param_type_name(param->type)) + ": " + why));
    }
  }

  for (const auto& [port, source] : node.inputs) {
    const PortInfo* input = type != nullptr ? type->input(port) : nullptr;
    if (type != nullptr && input == nullptr) {
      const std::vector<std::string> known = names_of(type->inputs);
      problems->push_back(problem_at(input_pointer(id, port),
                                     "unknown input port " + quoted(port) + " of node type " +
                                         quoted(type->name) + did_you_mean(port, known) +
                                         "; its inputs: " + join_names(known)));
    }
    auto source_node = graph.nodes.find(source.node);
    if (source_node == graph.nodes.end()) {
      problems->push_back(problem_at(input_pointer(id, port),
                                     "source " + quoted(source.str()) + " names node " +
                                         quoted(source.node) + ", which is not in the graph" +
                                         did_you_mean(source.node, ids)));
      continue;
    }
    const NodeType* source_type = registry.find(source_node->second.type);
    if (source_type == nullptr) continue;  // reported on the source node
    const PortInfo* output = source_type->output(source.port);
    if (output == nullptr) {
      const std::vector<std::string> known = names_of(source_type->outputs);
      problems->push_back(problem_at(
          input_pointer(id, port),
          "source " + quoted(source.str()) + ": node " + quoted(source.node) + " (type " +
              quoted(source_type->name) + ") has no output " + quoted(source.port) +
              did_you_mean(source.port, known) + "; its outputs: " + join_names(known)));
      continue;
    }
    if (input != nullptr && input->type != output->type) {
      problems->push_back(
          problem_at(input_pointer(id, port),
                     "input " + quoted(port) + " takes " + port_type_name(input->type) + " but " +
                         quoted(source.str()) + " gives " + port_type_name(output->type) +
                         "; connect an output of type " + port_type_name(input->type)));
    }
  }

  if (type == nullptr) return;
  for (const PortInfo& input : type->inputs) {
    const size_t links = node.inputs.count(input.name);
    if (links > 1 && !input.multi) {
      problems->push_back(problem_at(
          input_pointer(id, input.name),
          "input " + quoted(input.name) + " takes one link, not " + std::to_string(links) +
              ": give one source \"<node>.<port>\" (only ports that take many, such as "
              "scene_join's `objects`, accept an array)"));
    }
  }
  for (const PortInfo& input : type->inputs) {
    if (input.optional || node.inputs.count(input.name) != 0 ||
        already.inputs.count({id, input.name}) != 0) {
      continue;
    }
    problems->push_back(problem_at(
        input_pointer(id, input.name),
        "required input " + quoted(input.name) + " (" + port_type_name(input.type) +
            ") is not connected: add \"inputs\": {\"" + input.name + "\": \"<node>.<port>\"}"));
  }
}

// Cycles along input edges, found by an iterative depth-first search (a 10,000-node chain
// must not exhaust the stack). Each cycle is reported once, its nodes in data-flow order.
void check_cycles(const Graph& graph, std::vector<Problem>* problems) {
  std::vector<const std::string*> ids;
  std::unordered_map<std::string, size_t> index_of;
  for (const auto& entry : graph.nodes) {
    index_of.emplace(entry.first, ids.size());
    ids.push_back(&entry.first);
  }
  struct Edge {
    size_t source;
    const std::string* port;
  };
  std::vector<std::vector<Edge>> sources(ids.size());
  for (const auto& [id, node] : graph.nodes) {
    for (const auto& [port, ref] : node.inputs) {
      auto it = index_of.find(ref.node);
      if (it != index_of.end()) sources[index_of[id]].push_back(Edge{it->second, &port});
    }
  }

  enum class Mark { unvisited, on_path, done };
  std::vector<Mark> marks(ids.size(), Mark::unvisited);
  struct Frame {
    size_t node;
    size_t next_edge;
  };
  for (size_t root = 0; root < ids.size(); ++root) {
    if (marks[root] != Mark::unvisited) continue;
    std::vector<Frame> path{{root, 0}};
    marks[root] = Mark::on_path;
    while (!path.empty()) {
      Frame& frame = path.back();
      if (frame.next_edge == sources[frame.node].size()) {
        marks[frame.node] = Mark::done;
        path.pop_back();
        continue;
      }
      const Edge edge = sources[frame.node][frame.next_edge++];
      if (marks[edge.source] == Mark::unvisited) {
        marks[edge.source] = Mark::on_path;
        path.push_back(Frame{edge.source, 0});
        continue;
      }
      if (marks[edge.source] != Mark::on_path) continue;
      // Back edge: the path from edge.source to here is the cycle. Each node on the path
      // consumes the next one, so data flows in reverse path order.
      size_t start = path.size();
      while (path[start - 1].node != edge.source) --start;
      --start;
      const std::string& consumer = *ids[path.back().node];
      std::string chain = quoted(*ids[edge.source]);
      for (size_t i = path.size(); i > start + 1; --i)
        chain += " -> " + quoted(*ids[path[i - 1].node]);
      chain += " -> " + quoted(*ids[edge.source]);
      const std::string message =
          path.size() - start == 1
              ? "cycle: node " + quoted(consumer) + " feeds itself through input " +
                    quoted(*edge.port) + "; remove that input"
              : "cycle: " + chain + " (each feeds the next); remove one of these connections";
      problems->push_back(problem_at(input_pointer(consumer, *edge.port), message));
    }
  }
}

void check_output(const Graph& graph, const Registry& registry, const AlreadyReported& already,
                  std::vector<Problem>* problems) {
  if (!graph.output) {
    if (!already.output) {
      problems->push_back(problem_at(
          "/output", "no \"output\": name the port to render, e.g. \"output\": \"tint.image\""));
    }
    return;
  }
  const PortRef& output = *graph.output;
  auto node = graph.nodes.find(output.node);
  if (node == graph.nodes.end()) {
    std::vector<std::string> ids;
    for (const auto& entry : graph.nodes) ids.push_back(entry.first);
    problems->push_back(problem_at(
        "/output", "output " + quoted(output.str()) + " names node " + quoted(output.node) +
                       ", which is not in the graph" + did_you_mean(output.node, ids)));
    return;
  }
  const NodeType* type = registry.find(node->second.type);
  if (type == nullptr) return;  // reported on the node
  const PortInfo* port = type->output(output.port);
  if (port == nullptr) {
    const std::vector<std::string> known = names_of(type->outputs);
    problems->push_back(problem_at(
        "/output", "output " + quoted(output.str()) + ": node " + quoted(output.node) + " (type " +
                       quoted(type->name) + ") has no output " + quoted(output.port) +
                       did_you_mean(output.port, known) + "; its outputs: " + join_names(known)));
    return;
  }
  if (port->type != AQ_PORT_IMAGE) {
    problems->push_back(problem_at("/output", "output " + quoted(output.str()) + " is a " +
                                                  port_type_name(port->type) +
                                                  "; only an image can be rendered"));
  }
}

}  // namespace

Problem problem_at(const std::string& pointer, std::string message) {
  Problem problem;
  problem.pointer = pointer;
  problem.message = std::move(message);
  const std::vector<std::string> segments = json_text::split_pointer(pointer);
  if (segments.size() >= 2 && segments[0] == "nodes") {
    problem.node = segments[1];
    if (segments.size() >= 4 && (segments[2] == "params" || segments[2] == "inputs")) {
      problem.field = segments[3];
    }
  } else if (segments.size() >= 2 && segments[0] == "settings") {
    problem.field = segments[1];
  }
  return problem;
}

std::string node_pointer(const std::string& node_id) {
  return "/nodes/" + json_text::escape_pointer_segment(node_id);
}
std::string param_pointer(const std::string& node_id, const std::string& param) {
  return node_pointer(node_id) + "/params/" + json_text::escape_pointer_segment(param);
}
std::string input_pointer(const std::string& node_id, const std::string& port) {
  return node_pointer(node_id) + "/inputs/" + json_text::escape_pointer_segment(port);
}

std::string json_kind(const nlohmann::json& value) {
  if (value.is_number_integer()) return "an integer";
  if (value.is_number()) return "a number";
  if (value.is_string()) return "a string";
  if (value.is_boolean()) return "a boolean";
  if (value.is_array()) return "an array";
  if (value.is_object()) return "an object";
  return "null";
}

std::string quoted(const std::string& text) {
  return "'" + text + "'";
}

std::string join_names(const std::vector<std::string>& names) {
  if (names.empty()) return "(none)";
  std::string text;
  for (const std::string& name : names) {
    if (!text.empty()) text += ", ";
    text += name;
  }
  return text;
}

std::string did_you_mean(const std::string& wanted, const std::vector<std::string>& names) {
  const std::string* best = nullptr;
  size_t best_distance = std::max<size_t>(1, wanted.size() / 3) + 1;
  for (const std::string& name : names) {
    // The distance is at least the difference in length: skip names that cannot be closer.
    const size_t length_gap =
        name.size() > wanted.size() ? name.size() - wanted.size() : wanted.size() - name.size();
    if (length_gap >= best_distance) continue;
    const size_t distance = edit_distance(wanted, name);
    if (distance < best_distance) {
      best = &name;
      best_distance = distance;
    }
  }
  return best != nullptr ? " (did you mean " + quoted(*best) + "?)" : "";
}

bool is_valid_node_id(const std::string& id) {
  if (id.empty()) return false;
  const char first = id[0];
  if (!((first >= 'A' && first <= 'Z') || (first >= 'a' && first <= 'z') || first == '_')) {
    return false;
  }
  return std::all_of(id.begin(), id.end(), [](char c) {
    return (c >= 'A' && c <= 'Z') || (c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') || c == '_' ||
           c == '-';
  });
}

// A bypassed node that something reads must have an input to pass through (bypass.h).
void check_bypass(const Graph& graph, const Registry& registry, std::vector<Problem>* problems) {
  if (!has_bypassed_nodes(graph)) return;
  std::set<std::string> reported;
  auto check = [&](const PortRef& read) {
    auto node = graph.nodes.find(read.node);
    if (node == graph.nodes.end() || !node->second.bypass || reported.count(read.node)) return;
    auto source = bypass_source(graph, registry, read);
    if (source.ok()) return;
    reported.insert(read.node);
    problems->push_back(problem_at(node_pointer(read.node) + "/bypass", source.message()));
  };
  for (const auto& [id, node] : graph.nodes) {
    for (const auto& [port, source] : node.inputs) check(source);
  }
  if (graph.output) check(*graph.output);
}

std::vector<Problem> check_graph(const Graph& graph, const Registry& registry,
                                 const AlreadyReported& already_reported) {
  std::vector<Problem> problems;
  if (graph.version != 1) {
    problems.push_back(problem_at(
        "/aquarelle",
        "unsupported version " + std::to_string(graph.version) + "; this build reads version 1"));
  }
  check_settings(graph.settings, &problems);
  if (graph.output) {
    if (std::string why = node_count_problem(graph, *graph.output); !why.empty()) {
      problems.push_back(problem_at("/output", why));
    }
  }
  std::vector<std::string> ids;
  ids.reserve(graph.nodes.size());
  for (const auto& entry : graph.nodes) ids.push_back(entry.first);
  for (const auto& [id, node] : graph.nodes) {
    check_node(id, node, graph, ids, registry, already_reported, &problems);
  }
  check_cycles(graph, &problems);
  check_output(graph, registry, already_reported, &problems);
  check_bypass(graph, registry, &problems);
  return problems;
}

}  // namespace graph_checks

std::vector<Problem> validate_graph(const Graph& graph, const Registry& registry) {
  return graph_checks::check_graph(graph, registry, graph_checks::AlreadyReported{});
}

nlohmann::json param_value_or_default(const Node& node, const ParamInfo& param) {
  auto it = node.params.find(param.name);
  if (it != node.params.end()) return it->second;
  switch (param.type) {
    case AQ_PARAM_FLOAT:
      return param.default_value[0];
    case AQ_PARAM_INT:
      return static_cast<int64_t>(param.default_value[0]);
    case AQ_PARAM_BOOL:
      return param.default_value[0] != 0.0;
    case AQ_PARAM_ENUM: {
      const auto index = static_cast<size_t>(param.default_value[0]);
      return index < param.enum_values.size() ? nlohmann::json(param.enum_values[index])
                                              : nlohmann::json();
    }
    case AQ_PARAM_STRING:
    case AQ_PARAM_PATH:
      return param.default_string;
    case AQ_PARAM_COLOR:
    case AQ_PARAM_VEC3:
      return nlohmann::json::array(
          {param.default_value[0], param.default_value[1], param.default_value[2]});
  }
  return nlohmann::json();
}

std::string frame_range_problem(long long first, long long last) {
  if (first > last) return "the first frame must not come after the last";
  if (first < -kMaxFrameNumber || last > kMaxFrameNumber) {
    return "frame numbers must lie in -" + std::to_string(kMaxFrameNumber) + ".." +
           std::to_string(kMaxFrameNumber);
  }
  if (last - first + 1 > kMaxFrameCount) {
    return "a range holds at most " + std::to_string(kMaxFrameCount) +
           " frames; render it in parts";
  }
  return "";
}

std::string node_count_problem(const Graph& graph, const PortRef& output) {
  std::set<std::string> seen{output.node};
  std::vector<std::string> next{output.node};
  while (!next.empty() && seen.size() <= kMaxGraphNodes) {
    auto node = graph.nodes.find(next.back());
    next.pop_back();
    if (node == graph.nodes.end()) continue;
    for (const auto& [port, source] : node->second.inputs) {
      if (seen.insert(source.node).second) next.push_back(source.node);
    }
  }
  if (seen.size() <= kMaxGraphNodes) return "";
  return "the output '" + output.str() + "' depends on more than " +
         std::to_string(kMaxGraphNodes) +
         " nodes, and each is work every frame: merge repeated nodes (e.g. one erode of a "
         "larger size) or split the graph into several renders";
}

}  // namespace aq
