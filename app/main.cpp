// `aquarelle`: dispatches to the subcommands. Exit codes: 0 ok, 1 bad input (graph,
// arguments, files), 2 environment (no GL, unusable plugin path).
#include <cstdio>
#include <cstring>
#include <string>

#include "commands.h"
#ifdef AQ_HAVE_EDITOR
#include "editor/editor.h"
#endif

namespace {

void print_usage(std::FILE* out) {
  std::fprintf(out,
               "aquarelle %s: a node-graph compositor for stylized real-time rendering\n\n"
               "usage: aquarelle <command> [options]\n\n"
               "commands:\n"
               "  render    render a graph headless to image files\n"
               "  validate  check a graph file and list every problem\n"
               "  nodes     list the installed node types, their ports and parameters\n"
               "  bench     measure speed against error per node and for the pipeline\n"
               "  edit      open the graph editor\n\n"
               "`aquarelle <command> --help` describes each command.\n"
               "Exit codes: 0 ok, 1 bad input (graph, arguments, files), 2 environment.\n",
               AQ_VERSION);
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 2) {
    print_usage(stderr);
    return 1;
  }
  std::string command = argv[1];
  if (command == "--help" || command == "-h" || command == "help") {
    print_usage(stdout);
    return 0;
  }
  if (command == "--version") {
    std::printf("aquarelle %s\n", AQ_VERSION);
    return 0;
  }
  if (command == "render") return aq::app::run_render(argc - 1, argv + 1);
  if (command == "validate") return aq::app::run_validate(argc - 1, argv + 1);
  if (command == "nodes") return aq::app::run_nodes(argc - 1, argv + 1);
  if (command == "bench") return aq::app::run_bench(argc - 1, argv + 1);
  if (command == "edit") {
#ifdef AQ_HAVE_EDITOR
    return run_editor(argc - 1, argv + 1);
#else
    std::fprintf(stderr, "aquarelle: this build has no editor (configure with "
                         "-DAQUARELLE_BUILD_EDITOR=ON and install libglfw3-dev, libimgui-dev)\n");
    return 2;
#endif
  }
  std::fprintf(stderr, "aquarelle: unknown command '%s'\n\n", command.c_str());
  print_usage(stderr);
  return 1;
}
