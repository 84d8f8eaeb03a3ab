// The add-node search. See node_search.h.
#include "node_search.h"

#include <algorithm>
#include <cctype>
#include <tuple>

namespace aq::editor {

namespace {

std::string lower(std::string text) {
  for (char& c : text) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return text;
}

// Lower is better; -1: no match.
int rank_of(const NodeType& type, const std::string& needle) {
  const std::string name = lower(type.name);
  if (name == needle) return 0;
  if (name.rfind(needle, 0) == 0) return 1;
  if (name.find(needle) != std::string::npos) return 2;
  if (lower(type.category).find(needle) != std::string::npos) return 3;
  if (lower(type.description).find(needle) != std::string::npos) return 4;
  return -1;
}

}  // namespace

std::vector<const NodeType*> search_node_types(const Registry& registry,
                                               const std::string& filter) {
  const std::string needle = lower(filter);
  std::vector<std::tuple<int, size_t, std::string, const NodeType*>> found;
  if (needle.empty()) return {};
  for (const auto& [name, type] : registry.types()) {
    const int rank = rank_of(type, needle);
    if (rank >= 0) found.emplace_back(rank, rank <= 2 ? name.size() : 0, name, &type);
  }
  std::sort(found.begin(), found.end(), [](const auto& a, const auto& b) {
    return std::tie(std::get<0>(a), std::get<1>(a), std::get<2>(a)) <
           std::tie(std::get<0>(b), std::get<1>(b), std::get<2>(b));
  });
  std::vector<const NodeType*> types;
  for (const auto& entry : found) types.push_back(std::get<3>(entry));
  return types;
}

}  // namespace aq::editor
