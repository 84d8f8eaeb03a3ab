// The add-node menu's search: node types matching what the user typed, best first. A match in
// the name ranks before one in the category, which ranks before one in the description (Tab,
// "noise", Enter adds `noise`, not `control_map`, whose description mentions noise). No GL.
#pragma once

#include <aquarelle/core/registry.h>

#include <string>
#include <vector>

namespace aq::editor {

// Types whose name, category or description contains `filter` (case-insensitive), ranked:
// the exact name, names starting with it, names containing it (shorter names first), then
// category matches, then description matches; ties by name. An empty filter matches none.
std::vector<const NodeType*> search_node_types(const Registry& registry, const std::string& filter);

}  // namespace aq::editor
