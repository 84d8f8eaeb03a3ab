// `aquarelle validate GRAPH`: exit 0 when the graph is valid, else 1 with every problem.
#include <cstdio>

#include "commands.h"
#include "session.h"

namespace aq::app {

int run_validate(int argc, char** argv) {
  std::string graph_path;
  bool quiet = false;
  for (int i = 1; i < argc; ++i) {
    std::string arg = argv[i];
    if (arg == "--help" || arg == "-h") {
      std::printf(
          "usage: aquarelle validate GRAPH [-q]\n\n"
          "Reads GRAPH and lists every problem with its place in the file: malformed JSON,\n"
          "unsupported version, unknown node types, ports and parameters, missing inputs,\n"
          "type mismatches, cycles, out-of-range values, a bad `output`; then the files it\n"
          "names: missing or unreadable paths, images and meshes that are not, and (warnings)\n"
          "missing textures and material files.\n"
          "Exit codes: 0 valid, 1 problems found, 2 no plugins could be loaded.\n");
      return kExitOk;
    }
    if (arg == "-q" || arg == "--quiet") {
      quiet = true;
    } else if (!arg.empty() && arg[0] == '-') {
      std::fprintf(stderr, "aquarelle validate: unknown option '%s'\n", arg.c_str());
      return kExitBadInput;
    } else if (graph_path.empty()) {
      graph_path = arg;
    } else {
      std::fprintf(stderr, "aquarelle validate: one graph at a time ('%s')\n", arg.c_str());
      return kExitBadInput;
    }
  }
  if (graph_path.empty()) {
    std::fprintf(stderr, "aquarelle validate: no graph file given (see --help)\n");
    return kExitBadInput;
  }
  auto plugins = load_plugins(true);
  if (!plugins.ok()) {
    std::fprintf(stderr, "aquarelle validate: %s\n", plugins.message().c_str());
    return kExitEnvironment;
  }
  ReadResult read = read_graph_file(graph_path, (*plugins)->registry);
  if (!read.ok()) {
    std::fprintf(stderr, "%s\n", format_problems(read.problems).c_str());
    std::fprintf(stderr, "%s: %zu problem(s)\n", graph_path.c_str(), read.problems.size());
    return kExitBadInput;
  }
  const FileProblems files = check_graph_files(read.graph, (*plugins)->registry);
  for (const Problem& warning : files.warnings) {
    std::fprintf(stderr, "warning: %s\n", format_problem(warning).c_str());
  }
  if (!files.errors.empty()) {
    std::fprintf(stderr, "%s\n", format_problems(files.errors).c_str());
    std::fprintf(stderr, "%s: %zu problem(s)\n", graph_path.c_str(), files.errors.size());
    return kExitBadInput;
  }
  if (!quiet) {
    std::printf("%s: valid (%zu nodes, output %s)\n", graph_path.c_str(), read.graph.nodes.size(),
                read.graph.output ? read.graph.output->str().c_str() : "-");
  }
  return kExitOk;
}

}  // namespace aq::app
