// Shared set-up of the subcommands: plugins, overrides, and the values of --size and --frames.
#include "session.h"

#include <cstdio>
#include <regex>

namespace aq::app {

Result<std::unique_ptr<Plugins>> load_plugins(bool quiet) {
  auto plugins = std::make_unique<Plugins>();
  register_builtin_nodes(plugins->registry);
  auto path = default_plugin_path();
  plugins->report = plugins->set.load(path, plugins->registry);
  if (!quiet) {
    for (const auto& refused : plugins->report.refused) {
      std::fprintf(stderr, "warning: plugin %s\n", refused.c_str());
    }
  }
  if (plugins->report.loaded.empty()) {
    std::string searched;
    for (const auto& dir : path) searched += "\n  " + dir;
    return make_error("no plugin could be loaded from the plugin path:" + searched +
                      "\nBuild the project (cmake --build build) or set AQUARELLE_PLUGIN_PATH "
                      "to a folder of aquarelle_*.so plugins.");
  }
  return plugins;
}

Status apply_setting(Graph& graph, const Registry& registry, const std::string& assignment) {
  auto equals = assignment.find('=');
  if (equals == std::string::npos) {
    return make_error("--set '" + assignment + "': expected NODE.PARAM=VALUE");
  }
  auto target = PortRef::parse(assignment.substr(0, equals));
  if (!target) {
    return make_error("--set '" + assignment + "': expected NODE.PARAM=VALUE");
  }
  auto node = graph.nodes.find(target->node);
  if (node == graph.nodes.end()) {
    std::string ids;
    for (const auto& [id, n] : graph.nodes) ids += (ids.empty() ? "" : ", ") + id;
    return make_error("--set '" + assignment + "': no node '" + target->node +
                      "' in the graph (nodes: " + ids + ")");
  }
  const NodeType* type = registry.find(node->second.type);
  if (type != nullptr && type->param(target->port) == nullptr) {
    std::string names;
    for (const auto& p : type->params) names += (names.empty() ? "" : ", ") + p.name;
    return make_error("--set '" + assignment + "': node '" + target->node + "' (" + type->name +
                      ") has no parameter '" + target->port + "' (parameters: " + names + ")");
  }
  std::string text = assignment.substr(equals + 1);
  nlohmann::json value = nlohmann::json::parse(text, nullptr, false);
  if (value.is_discarded()) value = text;
  node->second.params[target->port] = value;
  return Ok{};
}

Status parse_size(const std::string& text, int* width, int* height) {
  static const std::regex pattern(R"((\d{1,6})x(\d{1,6}))");
  std::smatch match;
  if (!std::regex_match(text, match, pattern)) {
    return make_error("--size '" + text + "': expected WIDTHxHEIGHT, e.g. 1280x720");
  }
  int w = std::stoi(match[1]);
  int h = std::stoi(match[2]);
  if (w < 1 || h < 1 || w > 16384 || h > 16384) {
    return make_error("--size '" + text + "': each side must be between 1 and 16384");
  }
  *width = w;
  *height = h;
  return Ok{};
}

Status parse_frames(const std::string& text, int* first, int* last) {
  static const std::regex pattern(R"((-?\d{1,9})(?:-(-?\d{1,9}))?)");
  std::smatch match;
  if (!std::regex_match(text, match, pattern)) {
    return make_error("--frames '" + text + "': expected A-B or A, e.g. 1-48");
  }
  int a = std::stoi(match[1]);
  int b = match[2].matched ? std::stoi(match[2]) : a;
  if (a > b) {
    return make_error("--frames '" + text + "': the first frame is after the last; write " +
                      std::to_string(b) + "-" + std::to_string(a));
  }
  *first = a;
  *last = b;
  return Ok{};
}

}  // namespace aq::app
