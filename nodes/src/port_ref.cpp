// PortRef::parse: "<node id>.<port>" as written in graph files. Node ids cannot hold '.', port
// names cannot either, so the last '.' is the separator.
#include <aquarelle/core/graph.h>

namespace aq {

std::optional<PortRef> PortRef::parse(const std::string& text) {
  const size_t dot = text.rfind('.');
  if (dot == std::string::npos || dot == 0 || dot + 1 == text.size()) return std::nullopt;
  return PortRef{text.substr(0, dot), text.substr(dot + 1)};
}

}  // namespace aq
