// `aquarelle validate GRAPH`: exit 0 when the graph is valid, else 1 with every problem.
#include <cstdio>
#include <memory>
#include <string>
#include <vector>

#include "commands.h"
#include "session.h"

namespace aq::app {

namespace {

constexpr const char* kValidateHelp =
    "usage: aquarelle validate GRAPH [-q]\n\n"
    "Reads GRAPH and lists every problem with its place in the file: malformed JSON,\n"
    "unsupported version, unknown node types, ports and parameters, missing inputs,\n"
    "type mismatches, cycles, out-of-range values, a bad `output`; then the files it\n"
    "names: missing or unreadable paths, images and meshes that are not, and (warnings)\n"
    "missing textures and material files.";

struct ValidateArguments {
  std::vector<std::string> graphs;
  bool quiet = false;
};

int run_validate(const ValidateArguments& args) {
  if (args.graphs.empty()) {
    std::fprintf(stderr, "aquarelle validate: no graph file given (see --help)\n");
    return kExitBadInput;
  }
  if (args.graphs.size() > 1) {
    std::fprintf(stderr, "aquarelle validate: one graph at a time (%s)\n",
                 quote_for_message(args.graphs[1]).c_str());
    return kExitBadInput;
  }
  const std::string& graph_path = args.graphs[0];
  const bool quiet = args.quiet;
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

}  // namespace

Command add_validate_command(CLI::App& cli) {
  auto args = std::make_shared<ValidateArguments>();
  CLI::App* command =
      add_command(cli, "validate", "check a graph file and list every problem", kValidateHelp,
                  "Exit codes: 0 valid, 1 problems found, 2 no plugins could be "
                  "loaded.\n");
  command->add_option("GRAPH", args->graphs, "the graph file");
  command->add_flag("-q,--quiet", args->quiet, "say nothing when the graph is valid");
  return {command, [args] { return run_validate(*args); }};
}

}  // namespace aq::app
