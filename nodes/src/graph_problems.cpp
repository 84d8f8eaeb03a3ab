// Formatting graph problems the way compilers format diagnostics, so editors and terminals
// can jump to the place: "graph.json:12:7: node 'blur', parameter 'sigma': message".
#include <aquarelle/core/graph_io.h>
#include <aquarelle/core/message_text.h>

#include "json_locator.h"

namespace aq {
namespace {

// What kind of field a problem names, read from its pointer.
const char* field_kind(const Problem& problem) {
  const std::vector<std::string> segments = json_text::split_pointer(problem.pointer);
  if (segments.size() >= 3 && segments[0] == "nodes") {
    if (segments[2] == "params") return "parameter";
    if (segments[2] == "inputs") return "input";
  }
  if (!segments.empty() && segments[0] == "settings") return "setting";
  return "field";
}

}  // namespace

std::string format_problem(const Problem& problem) {
  // Every part is user text (a file name, a node id, a key): escaped, so a newline in one
  // cannot forge a `file:line:col: ...` line of its own.
  std::string place = escape_for_message(problem.file);
  if (problem.line > 0) {
    place += (place.empty() ? "" : ":") + std::to_string(problem.line);
    if (problem.column > 0) place += ":" + std::to_string(problem.column);
  } else if (!problem.pointer.empty()) {
    // Without a line (a model validated in memory) the pointer is the place.
    place += (place.empty() ? "" : ": ") + escape_for_message(problem.pointer);
  }
  std::string subject;
  if (!problem.node.empty()) subject = "node " + quote_for_message(problem.node);
  if (!problem.field.empty()) {
    subject += (subject.empty() ? "" : ", ") + std::string(field_kind(problem)) + " " +
               quote_for_message(problem.field);
  }
  std::string text = place;
  if (!subject.empty()) text += (text.empty() ? "" : ": ") + subject;
  text += (text.empty() ? "" : ": ") + escape_for_message(problem.message);
  return text;
}

std::string format_problems(const std::vector<Problem>& problems) {
  // One per line, without a final newline: callers print it with their own.
  // A screenful: past it the first problems are what to fix, the count says how many remain.
  constexpr size_t kShown = 40;
  std::string text;
  for (size_t i = 0; i < problems.size() && i < kShown; ++i) {
    if (!text.empty()) text += "\n";
    text += format_problem(problems[i]);
  }
  if (problems.size() > kShown) {
    text += "\n... and " + std::to_string(problems.size() - kShown) + " more problems";
  }
  return text;
}

}  // namespace aq
