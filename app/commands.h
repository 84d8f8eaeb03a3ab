// The subcommands of `aquarelle`. Each add_*_command declares its options on the command line
// (CLI11, cli.h) and returns how to run it once parsed; running returns the exit code.
#pragma once

#include <functional>

#include <aquarelle/core/message_text.h>  // arguments echoed in messages are escaped

#include "cli.h"

namespace aq::app {

enum ExitCode { kExitOk = 0, kExitBadInput = 1, kExitEnvironment = 2, kExitInterrupted = 130 };

struct Command {
  CLI::App* cli = nullptr;
  std::function<int()> run;
};

Command add_render_command(CLI::App& cli);
Command add_validate_command(CLI::App& cli);
Command add_nodes_command(CLI::App& cli);
Command add_bench_command(CLI::App& cli);
Command add_edit_command(CLI::App& cli);

}  // namespace aq::app
