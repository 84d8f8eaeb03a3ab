// Loads plugins from the plugin path only: the build's plugin folder, the install's plugin
// folder and AQUARELLE_PLUGIN_PATH. A graph file never names code to load. A plugin of another
// ABI version, without the entry point, or with an invalid description is refused with a
// message naming the file and the reason; the others still load.
#pragma once

#include <aquarelle/core/registry.h>

#include <memory>
#include <string>
#include <vector>

namespace aq {

struct PluginLoadReport {
  std::vector<std::string> loaded;   // files
  std::vector<std::string> refused;  // "FILE: reason"
};

class PluginLibrary;  // one dlopen'ed file

class PluginSet {
 public:
  PluginSet();
  ~PluginSet();
  PluginSet(PluginSet&&) noexcept;
  PluginSet& operator=(PluginSet&&) noexcept;

  // Loads every *.so in `directories` (in order; the first type of a name wins) into `registry`.
  PluginLoadReport load(const std::vector<std::string>& directories, Registry& registry);
  // Loads one file (tests).
  bool load_file(const std::string& path, Registry& registry, std::string* why);

 private:
  std::vector<std::unique_ptr<PluginLibrary>> libraries_;
};

// The default plugin path: $AQUARELLE_PLUGIN_PATH (colon-separated), the install folder next
// to the executable (<exe>/../lib/aquarelle/plugins), and the build folder.
std::vector<std::string> default_plugin_path();
// The folders $AQUARELLE_PLUGIN_PATH names (colon-separated, empty items skipped), in order;
// the start of every plugin path (the executable's and the Python module's).
std::vector<std::string> plugin_path_from_environment();

// Registers the host's own node types (`read`, `image_input`) in the registry.
void register_builtin_nodes(Registry& registry);

}  // namespace aq
