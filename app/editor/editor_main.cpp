// `aquarelle edit`: parses the editor's command line, loads the plugins and runs the window.
#include "editor.h"

#include "editor_app.h"

#include <aquarelle/core/plugin_loader.h>
#include <aquarelle/core/registry.h>

#include <cstdio>
#include <cstring>
#include <string>

namespace {

void print_usage(std::FILE* out) {
  std::fputs(
      "usage: aquarelle edit [GRAPH] [options]\n"
      "\n"
      "Opens the graph editor on GRAPH (a new file when it does not exist yet).\n"
      "\n"
      "  --size WxH               window size (default 1280x800)\n"
      "  --script ACTIONS.json    run editor actions after the first frame (see "
      "app/editor/script.h)\n"
      "  --screenshot OUT.png     write the window's pixels after the script\n"
      "  --quit                   exit after the script and screenshot (status 1 if an action\n"
      "                           did not do what it expected)\n",
      out);
}

}  // namespace

int run_editor(int argc, char** argv) {
  aq::editor::EditorOptions options;
  for (int i = 1; i < argc; ++i) {
    std::string arg = argv[i];
    auto value = [&](const char* name) -> const char* {
      if (i + 1 >= argc) {
        std::fprintf(stderr, "aquarelle edit: %s needs a value\n", name);
        return nullptr;
      }
      return argv[++i];
    };
    if (arg == "-h" || arg == "--help") {
      print_usage(stdout);
      return 0;
    } else if (arg == "--script") {
      const char* v = value("--script");
      if (v == nullptr) return 2;
      options.script = v;
    } else if (arg == "--screenshot") {
      const char* v = value("--screenshot");
      if (v == nullptr) return 2;
      options.screenshot = v;
    } else if (arg == "--quit") {
      options.quit = true;
    } else if (arg == "--size") {
      const char* v = value("--size");
      if (v == nullptr) return 2;
      if (std::sscanf(v, "%dx%d", &options.width, &options.height) != 2 || options.width < 64 ||
          options.height < 64 || options.width > 16384 || options.height > 16384) {
        std::fprintf(stderr, "aquarelle edit: --size wants WxH, at least 64x64, e.g. 1280x800\n");
        return 2;
      }
    } else if (!arg.empty() && arg[0] == '-') {
      std::fprintf(stderr, "aquarelle edit: unknown option '%s'\n\n", arg.c_str());
      print_usage(stderr);
      return 2;
    } else if (options.graph.empty()) {
      options.graph = arg;
    } else {
      std::fprintf(stderr, "aquarelle edit: one graph at a time ('%s' and '%s')\n",
                   options.graph.c_str(), arg.c_str());
      return 2;
    }
  }

  aq::Registry registry;
  aq::register_builtin_nodes(registry);
  aq::PluginSet plugins;
  aq::PluginLoadReport report = plugins.load(aq::default_plugin_path(), registry);
  for (const auto& refused : report.refused) {
    std::fprintf(stderr, "aquarelle edit: plugin refused: %s\n", refused.c_str());
  }
  options.refused_plugins = report.refused;  // the editor shows them too
  // The app holds GL objects from plugins: it must go before the plugin libraries unload.
  int status = 0;
  {
    aq::editor::EditorApp app(registry, options);
    status = app.run();
  }
  return status;
}
