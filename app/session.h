// What every subcommand needs before it can work: the registry of installed node types, the
// graph read from its file with command-line overrides applied, and a GL context.
#pragma once

#include <aquarelle/core/gl_context.h>
#include <aquarelle/core/graph.h>
#include <aquarelle/core/graph_io.h>
#include <aquarelle/core/plugin_loader.h>
#include <aquarelle/core/registry.h>
#include <aquarelle/core/result.h>

#include <memory>
#include <string>
#include <vector>

namespace aq::app {

struct Plugins {
  Registry registry;
  PluginSet set;
  PluginLoadReport report;
};

// Loads the host's built-in types and every plugin on the plugin path. Refused plugins are
// reported on stderr (unless quiet); returns an error only when the path holds no plugin.
Result<std::unique_ptr<Plugins>> load_plugins(bool quiet);

// "--set NODE.PARAM=VALUE": VALUE is JSON when it parses as JSON, else a string.
Status apply_setting(Graph& graph, const Registry& registry, const std::string& assignment);
// "WxH" -> width, height within [1, 16384].
Status parse_size(const std::string& text, int* width, int* height);
// "A-B" or "A" -> first, last with first <= last.
Status parse_frames(const std::string& text, int* first, int* last);

}  // namespace aq::app
