// A node's problems as advice. See node_advice.h.
#include "node_advice.h"

#include "canvas_view.h"

namespace aq::editor {

std::vector<std::string> node_advice(const Document& doc, const std::string& id,
                                     const std::string& evaluation_error) {
  std::vector<std::string> messages;
  auto node = doc.graph().nodes.find(id);
  if (node != doc.graph().nodes.end() && doc.registry().find(node->second.type) == nullptr) {
    messages.push_back("type '" + node->second.type + "' is not installed");
  }
  for (const auto& problem : doc.problems_of(id)) messages.push_back(problem.message);
  return node_reasons(messages, evaluation_error);
}

}  // namespace aq::editor
