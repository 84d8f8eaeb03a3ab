// `aquarelle nodes [TYPE] [--json]`: the installed node types with ports and parameters, read
// from the plugins' descriptions (the same data the validator and the editor use).
#include <cstdio>

#include "commands.h"
#include "session.h"

namespace aq::app {

namespace {

nlohmann::json param_json(const ParamInfo& p) {
  nlohmann::json j = {{"name", p.name}, {"type", param_type_name(p.type)},
                      {"description", p.description}};
  switch (p.type) {
    case AQ_PARAM_FLOAT:
      j["default"] = p.default_value[0];
      j["min"] = p.min_value;
      j["max"] = p.max_value;
      break;
    case AQ_PARAM_INT:
      j["default"] = static_cast<int64_t>(p.default_value[0]);
      j["min"] = static_cast<int64_t>(p.min_value);
      j["max"] = static_cast<int64_t>(p.max_value);
      break;
    case AQ_PARAM_BOOL: j["default"] = p.default_value[0] != 0; break;
    case AQ_PARAM_ENUM:
      j["values"] = p.enum_values;
      if (!p.enum_values.empty()) {
        j["default"] = p.enum_values[static_cast<size_t>(p.default_value[0]) %
                                     p.enum_values.size()];
      }
      break;
    case AQ_PARAM_COLOR:
    case AQ_PARAM_VEC3:
      j["default"] = {p.default_value[0], p.default_value[1], p.default_value[2]};
      break;
    case AQ_PARAM_STRING:
    case AQ_PARAM_PATH: j["default"] = p.default_string; break;
  }
  return j;
}

nlohmann::json type_json(const NodeType& t) {
  nlohmann::json j = {{"type", t.name},
                      {"category", t.category},
                      {"description", t.description},
                      {"time_dependent", t.time_dependent()},
                      {"pointwise", t.pointwise()},
                      {"plugin", t.plugin_file}};
  j["inputs"] = nlohmann::json::array();
  for (const auto& p : t.inputs) {
    j["inputs"].push_back({{"name", p.name},
                           {"type", port_type_name(p.type)},
                           {"optional", p.optional},
                           {"description", p.description}});
  }
  j["outputs"] = nlohmann::json::array();
  for (const auto& p : t.outputs) {
    j["outputs"].push_back(
        {{"name", p.name}, {"type", port_type_name(p.type)}, {"description", p.description}});
  }
  j["params"] = nlohmann::json::array();
  for (const auto& p : t.params) j["params"].push_back(param_json(p));
  return j;
}

void print_type(const NodeType& t) {
  std::printf("%s  [%s]%s%s\n  %s\n", t.name.c_str(), t.category.c_str(),
              t.time_dependent() ? " time-dependent" : "", t.pointwise() ? " pointwise" : "",
              t.description.c_str());
  for (const auto& p : t.inputs) {
    std::printf("  in  %-12s %-6s%s %s\n", p.name.c_str(), port_type_name(p.type),
                p.optional ? " (optional)" : "", p.description.c_str());
  }
  for (const auto& p : t.outputs) {
    std::printf("  out %-12s %-6s %s\n", p.name.c_str(), port_type_name(p.type),
                p.description.c_str());
  }
  for (const auto& p : t.params) {
    std::string def = param_json(p).value("default", nlohmann::json()).dump();
    std::string range;
    if (p.type == AQ_PARAM_FLOAT || p.type == AQ_PARAM_INT) {
      char text[64];
      std::snprintf(text, sizeof(text), " [%g, %g]", p.min_value, p.max_value);
      range = text;
    } else if (p.type == AQ_PARAM_ENUM) {
      for (const auto& v : p.enum_values) range += (range.empty() ? " {" : "|") + v;
      range += "}";
    }
    std::printf("  par %-12s %-6s = %s%s  %s\n", p.name.c_str(), param_type_name(p.type),
                def.c_str(), range.c_str(), p.description.c_str());
  }
}

}  // namespace

int run_nodes(int argc, char** argv) {
  bool json = false;
  std::string only;
  for (int i = 1; i < argc; ++i) {
    std::string arg = argv[i];
    if (arg == "--help" || arg == "-h") {
      std::printf("usage: aquarelle nodes [TYPE] [--json]\n\n"
                  "Lists the installed node types (plugins on the plugin path and the host's\n"
                  "built-in ones) with their ports and parameters. --json prints them as JSON.\n");
      return kExitOk;
    }
    if (arg == "--json") {
      json = true;
    } else if (!arg.empty() && arg[0] == '-') {
      std::fprintf(stderr, "aquarelle nodes: unknown option '%s'\n", arg.c_str());
      return kExitBadInput;
    } else {
      only = arg;
    }
  }
  auto plugins = load_plugins(json);
  if (!plugins.ok()) {
    std::fprintf(stderr, "aquarelle nodes: %s\n", plugins.message().c_str());
    return kExitEnvironment;
  }
  const Registry& registry = (*plugins)->registry;
  if (!only.empty() && registry.find(only) == nullptr) {
    std::string names;
    for (const auto& n : registry.names()) names += (names.empty() ? "" : ", ") + n;
    std::fprintf(stderr, "aquarelle nodes: no node type '%s' (installed: %s)\n", only.c_str(),
                 names.c_str());
    return kExitBadInput;
  }
  nlohmann::json all = nlohmann::json::array();
  for (const auto& name : registry.names()) {
    if (!only.empty() && name != only) continue;
    const NodeType& type = *registry.find(name);
    if (json) {
      all.push_back(type_json(type));
    } else {
      print_type(type);
      std::printf("\n");
    }
  }
  if (json) std::printf("%s\n", all.dump(2).c_str());
  return kExitOk;
}

}  // namespace aq::app
