// `aquarelle edit`: the editor's command line. The window itself lives in app/editor/ and is
// built only with the editor (AQ_HAVE_EDITOR); without it the command says how to get it.
#include <cstdio>
#include <memory>
#include <string>
#include <vector>

#include <aquarelle/core/message_text.h>

#include "commands.h"
#ifdef AQ_HAVE_EDITOR
#include "editor/editor.h"
#include "editor/editor_app.h"
#endif

namespace aq::app {

namespace {

constexpr const char* kEditHelp =
    "usage: aquarelle edit [GRAPH] [options]\n\n"
    "Opens the graph editor on GRAPH (a new file when it does not exist yet).";

struct EditArguments {
  std::vector<std::string> graphs;
  std::string size, script, screenshot;
  bool quit = false;
};

int run_edit(const EditArguments& args) {
  if (args.graphs.size() > 1) {
    std::fprintf(stderr, "aquarelle edit: one graph at a time (%s and %s)\n",
                 quote_for_message(args.graphs[0]).c_str(),
                 quote_for_message(args.graphs[1]).c_str());
    return kExitBadInput;
  }
#ifdef AQ_HAVE_EDITOR
  aq::editor::EditorOptions options;
  if (!args.graphs.empty()) options.graph = args.graphs[0];
  options.script = args.script;
  options.screenshot = args.screenshot;
  options.quit = args.quit;
  if (!args.size.empty() &&
      (std::sscanf(args.size.c_str(), "%dx%d", &options.width, &options.height) != 2 ||
       options.width < 64 || options.height < 64 || options.width > 16384 ||
       options.height > 16384)) {
    std::fprintf(stderr, "aquarelle edit: --size wants WxH, at least 64x64, e.g. 1280x800\n");
    return kExitBadInput;
  }
  return run_editor(options);
#else
  std::fprintf(stderr,
               "aquarelle: this build has no editor (configure with "
               "-DAQUARELLE_BUILD_EDITOR=ON and install libglfw3-dev, libimgui-dev)\n");
  return kExitEnvironment;
#endif
}

}  // namespace

Command add_edit_command(CLI::App& cli) {
  auto args = std::make_shared<EditArguments>();
  CLI::App* command = add_command(cli, "edit", "open the graph editor", kEditHelp,
                                  "Exit codes: 0 ok, 1 bad input (or, with --quit, an action "
                                  "of the script did not do what it expected), 2 no editor in "
                                  "this build.\n");
  command->add_option("GRAPH", args->graphs, "the graph file (created on save)");
  command->add_option("--size", args->size, "window size (default 1280x800)")->type_name("WxH");
  command
      ->add_option("--script", args->script,
                   "run editor actions after the first frame (see app/editor/script.h)")
      ->type_name("ACTIONS.json");
  command
      ->add_option("--screenshot", args->screenshot, "write the window's pixels after the script")
      ->type_name("OUT.png");
  command->add_flag("--quit", args->quit,
                    "exit after the script and screenshot (status 1 if an action\n"
                    "did not do what it expected)");
  return {command, [args] { return run_edit(*args); }};
}

}  // namespace aq::app
