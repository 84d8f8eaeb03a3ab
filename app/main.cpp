// `aquarelle`: the command line (CLI11) and its subcommands. Exit codes: 0 ok, 1 bad input
// (graph, arguments, files), 2 environment (no GL, unusable plugin path), 130 interrupted.
#include <cstdio>
#include <string>
#include <vector>

#include <aquarelle/core/message_text.h>

#include "commands.h"

namespace {

constexpr const char* kUsage =
    "usage: aquarelle <command> [options]\n\n"
    "aquarelle " AQ_VERSION ": a node-graph compositor for stylized real-time rendering";
constexpr const char* kFooter =
    "`aquarelle <command> --help` describes each command.\n"
    "Exit codes: 0 ok, 1 bad input (graph, arguments, files), 2 environment, 130 interrupted.\n";

// No command, or one that does not exist: the usage on stderr, exit 1.
int refuse_command(const CLI::App& cli, const std::vector<std::string>& left) {
  if (!left.empty()) {
    std::vector<std::string> names;
    for (const CLI::App* command : cli.get_subcommands({})) names.push_back(command->get_name());
    const std::string guess = aq::app::closest(left.front(), names);
    std::fprintf(stderr, "aquarelle: unknown command %s%s\n\n",
                 aq::quote_for_message(left.front()).c_str(),
                 guess.empty() ? "" : (" (did you mean '" + guess + "'?)").c_str());
  }
  std::fputs(cli.help().c_str(), stderr);
  return aq::app::kExitBadInput;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App cli(kUsage, "aquarelle");
  cli.formatter(aq::app::help_formatter());
  cli.footer(kFooter);
  cli.set_version_flag("--version", std::string("aquarelle ") + AQ_VERSION);
  cli.allow_extras();  // an unknown command is reported below, with a suggestion
  const std::vector<aq::app::Command> commands = {
      aq::app::add_render_command(cli), aq::app::add_validate_command(cli),
      aq::app::add_nodes_command(cli), aq::app::add_bench_command(cli),
      aq::app::add_edit_command(cli)};
  if (argc < 2) return refuse_command(cli, {});
  if (std::string(argv[1]) == "help") {  // `aquarelle help`, as before CLI11
    std::fputs(cli.help().c_str(), stdout);
    return aq::app::kExitOk;
  }
  if (auto stop = aq::app::parse_command_line(cli, argc, argv)) return *stop;
  for (const auto& command : commands) {
    if (!command.cli->parsed()) continue;
    if (auto unknown = aq::app::unknown_arguments(*command.cli); !unknown.empty()) {
      std::fprintf(stderr, "aquarelle %s: %s\n", command.cli->get_name().c_str(), unknown.c_str());
      return aq::app::kExitBadInput;
    }
    return command.run();
  }
  return refuse_command(cli, cli.remaining());
}
