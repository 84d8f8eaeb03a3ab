// `aquarelle nodes [TYPE] [--json]`: the installed node types with ports and parameters, read
// from the plugins' descriptions (the same data the validator and the editor use).
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <memory>
#include <string>
#include <vector>

#include "commands.h"
#include "session.h"

namespace aq::app {

namespace {

nlohmann::json param_json(const ParamInfo& p) {
  nlohmann::json j = {
      {"name", p.name}, {"type", param_type_name(p.type)}, {"description", p.description}};
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
    case AQ_PARAM_BOOL:
      j["default"] = p.default_value[0] != 0;
      break;
    case AQ_PARAM_ENUM:
      j["values"] = p.enum_values;
      if (!p.enum_values.empty()) {
        j["default"] =
            p.enum_values[static_cast<size_t>(p.default_value[0]) % p.enum_values.size()];
      }
      break;
    case AQ_PARAM_COLOR:
    case AQ_PARAM_VEC3:
      j["default"] = {p.default_value[0], p.default_value[1], p.default_value[2]};
      break;
    case AQ_PARAM_STRING:
    case AQ_PARAM_PATH:
      j["default"] = p.default_string;
      break;
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

// The measured cost and error of each quality preset, from the last `scripts/update-performance.sh`
// run (docs/performance/bench.json, installed as share/aquarelle/performance.json).
int print_presets() {
  namespace fs = std::filesystem;
  std::error_code ec;
  fs::path exe = fs::read_symlink("/proc/self/exe", ec);
  std::vector<fs::path> candidates = {
      exe.parent_path().parent_path() / "share/aquarelle/performance.json",
      fs::path(AQ_SOURCE_DIR) / "docs/performance/bench.json"};
  std::printf(
      "quality presets (settings.quality, or render --quality):\n"
      "  draft    renders at 1/4 of the graph's size, caustic grid / 8\n"
      "  preview  renders at 1/2 of the graph's size, caustic grid / 4\n"
      "  final    full size, every node at the parameters asked for (the default)\n\n");
  std::printf(
      "A proxy preset renders the nodes at the reduced size and resamples the output to\n"
      "the graph's size; parameters in pixels keep meaning output pixels\n"
      "(aq_process_ctx.render_scale). Each node also receives the preset\n"
      "(aq_process_ctx.quality); its README says what it changes.\n\n");
  for (const auto& path : candidates) {
    std::ifstream file(path);
    if (!file) continue;
    auto report = nlohmann::json::parse(file, nullptr, false);
    if (report.is_discarded() || !report.contains("sweeps")) continue;
    double copy_ms = report.value("copy_pass_ms", 0.0);
    std::printf("measured on %s at %s (%s):\n", report.value("graph", std::string("?")).c_str(),
                report["size"].dump().c_str(), path.string().c_str());
    std::printf("  %-8s %-6s %10s %12s %12s %8s\n", "preset", "prec.", "ms/frame", "copy passes",
                "mean abs err", "PSNR");
    for (const auto& sweep : report["sweeps"]) {
      if (sweep.value("node", std::string()) != "pipeline") continue;
      for (const auto& point : sweep["points"]) {
        if (point.value("is_reference", false)) continue;
        double ms = point["time_ms"].value("median", 0.0);
        std::printf("  %-8s %-6s %10.1f %12.1f %12.5f %8.1f\n",
                    point["params"].value("quality", std::string("?")).c_str(),
                    point.value("precision", std::string("?")).c_str(), ms,
                    copy_ms > 0 ? ms / copy_ms : 0.0, point.value("mean_abs", 0.0),
                    point.value("psnr", 0.0));
      }
    }
    std::printf(
        "\nerrors are against a float render at the final preset; regenerate with "
        "scripts/update-performance.sh\n");
    return kExitOk;
  }
  std::printf("no measurements found: run scripts/update-performance.sh (aquarelle bench)\n");
  return kExitOk;
}

constexpr const char* kNodesHelp =
    "usage: aquarelle nodes [TYPE] [--json] [--presets]\n\n"
    "Lists the installed node types (plugins on the plugin path and the host's\n"
    "built-in ones) with their ports and parameters. --json prints them as JSON;\n"
    "--presets prints the quality presets with their measured cost and error.";

struct NodesArguments {
  std::vector<std::string> types;  // the last one given is listed alone
  bool json = false;
  bool presets = false;
};

int run_nodes(const NodesArguments& args) {
  const bool json = args.json;
  const std::string only = args.types.empty() ? std::string() : args.types.back();
  auto plugins = load_plugins(json);
  if (!plugins.ok()) {
    std::fprintf(stderr, "aquarelle nodes: %s\n", plugins.message().c_str());
    return kExitEnvironment;
  }
  const Registry& registry = (*plugins)->registry;
  if (args.presets) return print_presets();
  if (!only.empty() && registry.find(only) == nullptr) {
    std::string names;
    for (const auto& n : registry.names()) names += (names.empty() ? "" : ", ") + n;
    std::fprintf(stderr, "aquarelle nodes: no node type %s (installed: %s)\n",
                 quote_for_message(only).c_str(), names.c_str());
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

}  // namespace

Command add_nodes_command(CLI::App& cli) {
  auto args = std::make_shared<NodesArguments>();
  CLI::App* command =
      add_command(cli, "nodes", "list the installed node types, their ports and parameters",
                  kNodesHelp, "Exit codes: 0 ok, 1 no such node type, 2 no plugins.\n");
  command->add_option("TYPE", args->types, "list only this node type");
  command->add_flag("--json", args->json, "print the node types as JSON");
  command->add_flag("--presets", args->presets,
                    "print the quality presets with their measured cost and error");
  return {command, [args] { return run_nodes(*args); }};
}

}  // namespace aq::app
