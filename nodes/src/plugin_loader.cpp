// PluginSet: dlopen's plugins from the plugin path and registers their node types.
#include <aquarelle/core/plugin_loader.h>
#include <aquarelle/sdk/regular_file.hpp>

#include <dlfcn.h>
#include <unistd.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <sstream>

namespace aq {

namespace fs = std::filesystem;

class PluginLibrary {
 public:
  explicit PluginLibrary(void* handle) : handle_(handle) {}
  ~PluginLibrary() {
    // Plugins stay mapped until exit: node instances and static descriptions may still be
    // referenced by registries that outlive this set in tests.
  }
  void* handle() const { return handle_; }

 private:
  void* handle_;
};

PluginSet::PluginSet() = default;
PluginSet::~PluginSet() = default;
PluginSet::PluginSet(PluginSet&&) noexcept = default;
PluginSet& PluginSet::operator=(PluginSet&&) noexcept = default;

bool PluginSet::load_file(const std::string& path, Registry& registry, std::string* why) {
  // dlopen blocks forever on a FIFO named *.so and reads a device without end: only regular
  // files are candidates (links are followed, as dlopen would).
  if (std::string problem = files::regular_file_problem(path); !problem.empty()) {
    *why = "cannot be opened: " + problem;
    return false;
  }
  void* handle = dlopen(path.c_str(), RTLD_NOW | RTLD_LOCAL);
  if (handle == nullptr) {
    const char* error = dlerror();
    *why = std::string("cannot be opened: ") + (error != nullptr ? error : "unknown error");
    return false;
  }
  auto entry = reinterpret_cast<aq_plugin_entry_fn>(dlsym(handle, AQ_PLUGIN_ENTRY_NAME));
  if (entry == nullptr) {
    *why = std::string("has no entry point '") + AQ_PLUGIN_ENTRY_NAME +
           "' (is it an Aquarelle plugin? build it with aquarelle_add_plugin and AQ_PLUGIN)";
    dlclose(handle);
    return false;
  }
  const aq_plugin_desc* desc = entry(AQ_ABI_VERSION);
  if (desc == nullptr) {
    *why = "refused to load into this host (its entry point returned no description)";
    dlclose(handle);
    return false;
  }
  if (desc->abi_version != AQ_ABI_VERSION) {
    *why = "was built for plugin ABI version " + std::to_string(desc->abi_version) +
           ", this host speaks version " + std::to_string(AQ_ABI_VERSION) +
           ": rebuild it against this release's SDK";
    dlclose(handle);
    return false;
  }
  if (desc->struct_size < sizeof(aq_plugin_desc) ||
      (desc->node_count > 0 && desc->nodes == nullptr)) {
    *why = "has an invalid plugin description (struct size or node list)";
    dlclose(handle);
    return false;
  }
  std::vector<NodeType> types;
  for (uint32_t i = 0; i < desc->node_count; ++i) {
    const aq_node_desc* node = desc->nodes[i];
    std::string reason;
    if (node == nullptr || node->struct_size < sizeof(aq_node_desc)) {
      *why = "node description " + std::to_string(i) + " is missing or too small";
      dlclose(handle);
      return false;
    }
    NodeType type = node_type_from_desc(*node, path, &reason);
    if (type.name.empty()) {
      *why = "node type '" + std::string(node->type_name ? node->type_name : "?") +
             "' is invalid: " + reason;
      dlclose(handle);
      return false;
    }
    types.push_back(std::move(type));
  }
  std::ostringstream refused;
  int added = 0;
  for (auto& type : types) {
    std::string reason;
    if (registry.add(std::move(type), &reason)) {
      ++added;
    } else {
      refused << (refused.tellp() > 0 ? "; " : "") << reason;
    }
  }
  libraries_.push_back(std::make_unique<PluginLibrary>(handle));
  if (added == 0 && !types.empty()) {
    *why = refused.str();
    return false;
  }
  if (refused.tellp() > 0) *why = refused.str();
  return true;
}

PluginLoadReport PluginSet::load(const std::vector<std::string>& directories, Registry& registry) {
  PluginLoadReport report;
  for (const auto& directory : directories) {
    std::error_code ec;
    if (!fs::is_directory(directory, ec)) continue;
    std::vector<std::string> files;
    for (const auto& entry : fs::directory_iterator(directory, ec)) {
      if (entry.path().extension() == ".so") files.push_back(entry.path().string());
    }
    std::sort(files.begin(), files.end());
    for (const auto& file : files) {
      std::string why;
      if (load_file(file, registry, &why)) {
        report.loaded.push_back(file);
        if (!why.empty()) report.refused.push_back(file + ": " + why);
      } else {
        report.refused.push_back(file + ": " + why);
      }
    }
  }
  return report;
}

std::vector<std::string> plugin_path_from_environment() {
  std::vector<std::string> path;
  if (const char* env = std::getenv("AQUARELLE_PLUGIN_PATH"); env != nullptr) {
    std::stringstream stream(env);
    std::string item;
    while (std::getline(stream, item, ':')) {
      if (!item.empty()) path.push_back(item);
    }
  }
  return path;
}

std::vector<std::string> default_plugin_path() {
  std::vector<std::string> path = plugin_path_from_environment();
  // An installed executable uses its installed plugins; one in the build tree, the build's.
  // Never both, or every type would be found twice.
  std::error_code ec;
  fs::path exe = fs::read_symlink("/proc/self/exe", ec);
  fs::path installed = ec ? fs::path() : exe.parent_path().parent_path() / AQ_PLUGIN_INSTALL_SUBDIR;
  if (!installed.empty() && fs::is_directory(installed, ec)) {
    path.push_back(installed.string());
  } else {
    path.push_back(AQ_PLUGIN_BUILD_DIR);
  }
  return path;
}

}  // namespace aq
