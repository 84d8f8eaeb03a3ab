// `aquarelle edit`: loads the plugins and runs the window (app/edit_command.cpp parses the
// command line).
#include "editor.h"

#include "editor_app.h"

#include <aquarelle/core/plugin_loader.h>
#include <aquarelle/core/registry.h>

#include <cstdio>

int run_editor(const aq::editor::EditorOptions& options) {
  aq::Registry registry;
  aq::register_builtin_nodes(registry);
  aq::PluginSet plugins;
  aq::PluginLoadReport report = plugins.load(aq::default_plugin_path(), registry);
  for (const auto& refused : report.refused) {
    std::fprintf(stderr, "aquarelle edit: plugin refused: %s\n", refused.c_str());
  }
  aq::editor::EditorOptions shown = options;
  shown.refused_plugins = report.refused;  // the editor shows them too
  // The app holds GL objects from plugins: it must go before the plugin libraries unload.
  int status = 0;
  {
    aq::editor::EditorApp app(registry, shown);
    status = app.run();
  }
  return status;
}
