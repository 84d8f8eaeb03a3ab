// The subcommands of `aquarelle`; each parses its own arguments and returns the exit code.
#pragma once

namespace aq::app {

enum ExitCode { kExitOk = 0, kExitBadInput = 1, kExitEnvironment = 2, kExitInterrupted = 130 };

int run_render(int argc, char** argv);
int run_validate(int argc, char** argv);
int run_nodes(int argc, char** argv);
int run_bench(int argc, char** argv);

}  // namespace aq::app
