// The command line's shared parts (cli.h).
#include "cli.h"

#include <aquarelle/core/message_text.h>

#include <algorithm>
#include <cstdio>
#include <map>
#include <sstream>

namespace aq::app {

namespace {

// Each command's help text (usage line first), by command; the description is its summary in
// the list of commands.
std::map<const CLI::App*, std::string>& help_texts() {
  static std::map<const CLI::App*, std::string> texts;
  return texts;
}

// CLI11's formatter, with the command's help text (its usage line first) in place of CLI11's
// description and "Usage:" line, and value names as the help writes them (OUT, WxH).
class HelpFormatter : public CLI::Formatter {
 public:
  HelpFormatter() { column_width(28); }
  std::string make_help(const CLI::App* app, std::string /*name*/,
                        CLI::AppFormatMode mode) const override {
    if (mode == CLI::AppFormatMode::Sub) return make_expanded(app);
    std::stringstream out;
    auto text = help_texts().find(app);
    out << (text != help_texts().end() ? text->second : app->get_description()) << "\n";
    out << make_positionals(app) << make_groups(app, mode) << make_subcommands(app, mode);
    const std::string footer = make_footer(app);
    if (!footer.empty()) out << "\n" << footer;
    return out.str();
  }
  std::string make_option_opts(const CLI::Option* option) const override {
    const bool positional = option->get_lnames().empty() && option->get_snames().empty();
    if (positional || option->get_type_size() == 0 || option->get_type_name().empty()) return "";
    return " " + option->get_type_name();
  }
};

size_t edit_distance(const std::string& a, const std::string& b) {
  std::vector<size_t> row(b.size() + 1);
  for (size_t j = 0; j <= b.size(); ++j) row[j] = j;
  for (size_t i = 1; i <= a.size(); ++i) {
    size_t diagonal = row[0];
    row[0] = i;
    for (size_t j = 1; j <= b.size(); ++j) {
      const size_t above = row[j];
      row[j] = std::min({row[j] + 1, row[j - 1] + 1, diagonal + (a[i - 1] == b[j - 1] ? 0 : 1)});
      diagonal = above;
    }
  }
  return row[b.size()];
}

}  // namespace

std::shared_ptr<CLI::Formatter> help_formatter() {
  static const auto formatter = std::make_shared<HelpFormatter>();
  return formatter;
}

CLI::App* add_command(CLI::App& cli, const std::string& name, const std::string& summary,
                      const std::string& help, const std::string& footer) {
  CLI::App* command = cli.add_subcommand(name, summary);
  command->formatter(help_formatter());
  command->footer(footer);
  command->allow_extras();  // reported by unknown_arguments, with a suggestion
  help_texts()[command] = help;
  command->group("Commands");
  return command;
}

std::string closest(const std::string& word, const std::vector<std::string>& candidates) {
  std::string best;
  size_t best_distance = std::max<size_t>(2, word.size() / 3) + 1;
  for (const auto& candidate : candidates) {
    const size_t distance = edit_distance(word, candidate);
    if (distance < best_distance) {
      best_distance = distance;
      best = candidate;
    }
  }
  return best;
}

std::vector<std::string> option_names(const CLI::App& command) {
  std::vector<std::string> names;
  for (const CLI::Option* option : command.get_options()) {
    for (const auto& name : option->get_lnames()) names.push_back("--" + name);
    for (const auto& name : option->get_snames()) names.push_back("-" + name);
  }
  return names;
}

std::string unknown_arguments(const CLI::App& command) {
  const std::vector<std::string> left = command.remaining();
  if (left.empty()) return "";
  std::string argument = left.front();
  // Arguments are echoed escaped, as every message is: a newline or an ESC sequence in one
  // would forge a line or clear the terminal.
  if (argument.size() < 2 || argument[0] != '-') {
    return "unexpected argument " + quote_for_message(argument);
  }
  argument = argument.substr(0, argument.find('='));  // --frmes=1-3
  const std::string guess = closest(argument, option_names(command));
  return "unknown option " + quote_for_message(argument) +
         (guess.empty() ? " (see --help)" : " (did you mean '" + guess + "'? see --help)");
}

std::optional<int> parse_command_line(CLI::App& cli, int argc, char** argv) {
  try {
    cli.parse(argc, argv);
    return std::nullopt;
  } catch (const CLI::CallForHelp&) {
    std::fputs(cli.help().c_str(), stdout);  // the selected command's help
    return 0;
  } catch (const CLI::CallForVersion& version) {
    std::printf("%s\n", version.what());
    return 0;
  } catch (const CLI::ParseError& error) {
    std::string who = cli.get_name();
    for (const CLI::App* command : cli.get_subcommands()) who += " " + command->get_name();
    std::string message = error.what();
    // CLI11 says "--size: 1 required WxH missing"; the commands have always said this:
    const size_t colon = message.find(':');
    if (error.get_name() == "ArgumentMismatch" && colon != std::string::npos &&
        message.find(" required ") != std::string::npos)
      message = message.substr(0, colon) + " needs a value";
    // CLI11 quotes the argument it refused: escaped like every other message.
    std::fprintf(stderr, "%s: %s (see --help)\n", who.c_str(), escape_for_message(message).c_str());
    return 1;
  }
}

}  // namespace aq::app
