// The command line's shared parts, on CLI11: one help style for every command (its usage line,
// what it does, its options, its exit codes), typo suggestions for unknown commands and
// options, and the mapping of parse errors to exit code 1.
#pragma once

#include <CLI/CLI.hpp>

#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace aq::app {

// Adds the subcommand `name` to `cli` with the shared help style: `help` starts with its usage
// line ("usage: aquarelle NAME ..."), then says what it does; `footer` ends the help (exit
// codes). Unknown arguments are left for the command to report (unknown_arguments).
CLI::App* add_command(CLI::App& cli, const std::string& name, const std::string& summary,
                      const std::string& help, const std::string& footer);

// The shared help style: usage line and description, then the options with their value names.
std::shared_ptr<CLI::Formatter> help_formatter();

// The closest of `candidates` to `word` (at most 2 edits, or a third of its length for long
// words), or empty: the "did you mean" of an unknown command or option.
std::string closest(const std::string& word, const std::vector<std::string>& candidates);

// Every name of `command`'s options ("-o", "--output", "--frames"...).
std::vector<std::string> option_names(const CLI::App& command);

// What an argument the command does not know means to the user: "unknown option '--frmes'
// (did you mean '--frames'? see --help)". Empty when nothing was left over.
std::string unknown_arguments(const CLI::App& command);

// Parses argv; returns the exit code when the program should stop here (help and --version:
// 0, printed to stdout; a parse error: 1, "aquarelle[ COMMAND]: message" on stderr).
std::optional<int> parse_command_line(CLI::App& cli, int argc, char** argv);

}  // namespace aq::app
