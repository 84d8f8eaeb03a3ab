// Node groups: a sub-graph drawn as one node on the canvas, kept in editor.groups. Presentation
// only: evaluation and `aquarelle render` read nodes and links, never the editor section, so a
// group changes no pixel. Each edit builds the edited graph on a copy and records the
// difference as one undoable change (Document::commit_edit).
#include "document.h"

#include "canvas_view.h"

#include <algorithm>
#include <cmath>
#include <set>

namespace aq::editor {

namespace {

constexpr const char* kGroupPrefix = "group.";

bool valid_position(const nlohmann::json& p) {
  return p.is_array() && p.size() == 2 && p[0].is_number() && p[1].is_number();
}

// A number as people write it: integers stay integers, so saved positions read like the rest.
nlohmann::json whole_or_float(float v) {
  if (std::floor(v) == v && std::fabs(v) < 1e9f) return static_cast<int64_t>(v);
  return v;
}

}  // namespace

Position members_top_left(const Graph& graph, const Registry& registry,
                          const std::vector<std::string>& members) {
  Position top_left{1e30f, 1e30f};
  for (const auto& id : members) {
    Rect r = node_rect(graph, registry, id);
    top_left = {std::min(top_left.x, r.min.x), std::min(top_left.y, r.min.y)};
  }
  if (top_left.x > 1e29f) return {};
  return {std::round(top_left.x), std::round(top_left.y)};
}

Status Document::rename_group(const std::string& name, const std::string& new_name) {
  auto groups = read_groups(graph_);
  auto it =
      std::find_if(groups.begin(), groups.end(), [&](const Group& g) { return g.name == name; });
  if (it == groups.end()) return make_error("no group named '" + name + "'");
  if (new_name == name) return Ok{};
  if (new_name.empty()) return make_error("cannot rename group '" + name + "': give it a name");
  if (std::any_of(groups.begin(), groups.end(),
                  [&](const Group& g) { return g.name == new_name; })) {
    return make_error("cannot rename group '" + name + "' to '" + new_name +
                      "': another group has that name");
  }
  it->name = new_name;
  Graph edited = graph_;
  write_groups(edited, groups);
  commit_edit("rename group " + name + " to " + new_name, edited);
  return Ok{};
}

std::string group_item_id(const std::string& name) {
  return kGroupPrefix + name;
}

std::optional<std::string> group_name_of_item(const std::string& item) {
  if (item.rfind(kGroupPrefix, 0) != 0) return std::nullopt;
  return item.substr(std::string(kGroupPrefix).size());
}

std::vector<Group> read_groups(const Graph& graph) {
  std::vector<Group> out;
  if (!graph.editor.is_object() || !graph.editor.contains("groups")) return out;
  const auto& list = graph.editor["groups"];
  if (!list.is_array()) return out;
  std::set<std::string> taken;  // a node belongs to one group at most: the first one wins
  for (const auto& item : list) {
    if (!item.is_object() || !item.contains("name") || !item["name"].is_string()) continue;
    Group group;
    group.name = item["name"].get<std::string>();
    for (const auto& id : item.value("nodes", nlohmann::json::array())) {
      if (id.is_string() && graph.nodes.count(id.get<std::string>()) &&
          taken.insert(id.get<std::string>()).second) {
        group.nodes.push_back(id.get<std::string>());
      }
    }
    const auto collapsed = item.find("collapsed");
    group.collapsed = collapsed == item.end() || !collapsed->is_boolean() || collapsed->get<bool>();
    const auto position = item.find("position");
    if (position != item.end() && valid_position(*position)) {
      group.position = {(*position)[0].get<float>(), (*position)[1].get<float>()};
    }
    if (!group.nodes.empty()) out.push_back(std::move(group));
  }
  return out;
}

void write_groups(Graph& graph, const std::vector<Group>& groups) {
  if (!graph.editor.is_object()) graph.editor = nlohmann::json::object();
  if (groups.empty()) {
    graph.editor.erase("groups");
    return;
  }
  nlohmann::json list = nlohmann::json::array();
  for (const auto& g : groups) {
    list.push_back({{"name", g.name},
                    {"nodes", g.nodes},
                    {"collapsed", g.collapsed},
                    {"position", {whole_or_float(g.position.x), whole_or_float(g.position.y)}}});
  }
  graph.editor["groups"] = list;
}

const Group* collapsed_group_of(const std::vector<Group>& groups, const std::string& id) {
  for (const auto& group : groups) {
    if (group.collapsed &&
        std::find(group.nodes.begin(), group.nodes.end(), id) != group.nodes.end()) {
      return &group;
    }
  }
  return nullptr;
}

GroupPorts group_ports(const Graph& graph, const Registry& registry, const Group& group) {
  GroupPorts ports;
  const std::set<std::string> members(group.nodes.begin(), group.nodes.end());
  // Which member outputs are read inside the group, and which outside (or give the output).
  std::set<std::pair<std::string, std::string>> read_inside;
  std::set<std::pair<std::string, std::string>> read_outside;
  std::set<std::string> member_read_inside;
  for (const auto& [id, node] : graph.nodes) {
    for (const auto& [port, source] : node.inputs) {
      if (!members.count(source.node)) continue;
      if (members.count(id)) {
        read_inside.insert({source.node, source.port});
        member_read_inside.insert(source.node);
      } else {
        read_outside.insert({source.node, source.port});
      }
    }
  }
  if (graph.output && members.count(graph.output->node)) {
    read_outside.insert({graph.output->node, graph.output->port});
  }
  // A group whose outputs nothing outside reads shows its last nodes' outputs as its result.
  const bool dangling = read_outside.empty();
  for (const auto& id : group.nodes) {
    const Node& node = graph.nodes.at(id);
    const NodeType* type = registry.find(node.type);
    if (type == nullptr) continue;
    for (const auto& input : type->inputs) {
      const auto links = node.inputs.links(input.name);
      const bool fed_inside = std::any_of(links.begin(), links.end(), [&](const PortRef& from) {
        return members.count(from.node) > 0;
      });
      const bool fed_outside = !links.empty() && !fed_inside;
      // Optional inputs left unlinked stay hidden (expand the group to link them).
      if (fed_outside || (links.empty() && !input.optional)) {
        ports.inputs.push_back({{id, input.name}, input.type});
      }
    }
    for (const auto& output : type->outputs) {
      const bool outside = read_outside.count({id, output.name}) > 0;
      const bool result = dangling && !member_read_inside.count(id);
      if (outside || result) ports.outputs.push_back({{id, output.name}, output.type});
    }
  }
  return ports;
}

std::vector<std::string> expand_group_items(const Graph& graph,
                                            const std::vector<std::string>& ids) {
  std::vector<std::string> out;
  std::set<std::string> seen;
  const auto groups = read_groups(graph);
  for (const auto& id : ids) {
    std::vector<std::string> members = {id};
    if (auto name = group_name_of_item(id)) {
      members.clear();
      for (const auto& group : groups) {
        if (group.name == *name) members = group.nodes;
      }
    }
    for (const auto& member : members) {
      if (seen.insert(member).second) out.push_back(member);
    }
  }
  return out;
}

Result<std::string> Document::group_nodes(const std::vector<std::string>& ids,
                                          const std::string& name) {
  const std::vector<std::string> members = expand_group_items(graph_, ids);
  if (members.empty()) return make_error("nothing to group: select the nodes to group first");
  auto groups = read_groups(graph_);
  for (const auto& id : members) {
    if (!graph_.nodes.count(id)) return make_error("cannot group '" + id + "': no such node");
    for (const auto& group : groups) {
      if (std::find(group.nodes.begin(), group.nodes.end(), id) != group.nodes.end()) {
        return make_error("cannot group '" + id + "': it is in group '" + group.name +
                          "' already; ungroup that first (Ctrl+Alt+G)");
      }
    }
  }
  auto taken = [&](const std::string& candidate) {
    return std::any_of(groups.begin(), groups.end(),
                       [&](const Group& g) { return g.name == candidate; });
  };
  std::string chosen = name;
  if (chosen.empty() || taken(chosen)) {
    const std::string base = name.empty() ? "Group" : name;
    chosen = base;
    for (int n = 2; taken(chosen); ++n) chosen = base + std::to_string(n);
  }
  const Position top_left = members_top_left(graph_, registry_, members);
  Graph edited = graph_;
  // Every member gets a saved position, so the group's drag moves what it shows.
  for (const auto& id : members) write_position(edited, id, node_position(graph_, id));
  groups.push_back({chosen, members, true, top_left});
  write_groups(edited, groups);
  commit_edit("group " + std::to_string(members.size()) + " nodes as " + chosen, edited);
  return chosen;
}

Status Document::set_group_collapsed(const std::string& name, bool collapsed) {
  Graph edited = graph_;
  auto groups = read_groups(graph_);
  auto it =
      std::find_if(groups.begin(), groups.end(), [&](const Group& g) { return g.name == name; });
  if (it == groups.end()) return make_error("no group named '" + name + "'");
  if (it->collapsed == collapsed) return Ok{};
  it->collapsed = collapsed;
  // Collapsed where its nodes are now (they may have moved while it was open).
  if (collapsed) it->position = members_top_left(graph_, registry_, it->nodes);
  write_groups(edited, groups);
  commit_edit((collapsed ? "collapse " : "expand ") + name, edited);
  return Ok{};
}

Status Document::ungroup(const std::string& name) {
  Graph edited = graph_;
  auto groups = read_groups(graph_);
  auto it =
      std::find_if(groups.begin(), groups.end(), [&](const Group& g) { return g.name == name; });
  if (it == groups.end()) return make_error("no group named '" + name + "'");
  groups.erase(it);
  write_groups(edited, groups);
  commit_edit("ungroup " + name, edited);
  return Ok{};
}

Status Document::move_with_groups(const std::map<std::string, Position>& positions,
                                  const std::string& coalesce_key) {
  Graph edited = graph_;
  auto groups = read_groups(graph_);
  for (const auto& [item, at] : positions) {
    auto name = group_name_of_item(item);
    if (!name) {
      if (!graph_.nodes.count(item))
        return make_error("cannot move node '" + item + "': no such node");
      write_position(edited, item, at);
      continue;
    }
    auto group =
        std::find_if(groups.begin(), groups.end(), [&](const Group& g) { return g.name == *name; });
    if (group == groups.end())
      return make_error("cannot move group '" + *name + "': no such group");
    const Position to{std::round(at.x), std::round(at.y)};
    const Position by{to.x - group->position.x, to.y - group->position.y};
    for (const auto& id : group->nodes) {
      const Position was = node_position(graph_, id);
      write_position(edited, id, Position{was.x + by.x, was.y + by.y});
    }
    group->position = to;
  }
  write_groups(edited, groups);
  commit_edit(positions.size() == 1 ? "move " + positions.begin()->first
                                    : "move " + std::to_string(positions.size()) + " items",
              edited, coalesce_key);
  return Ok{};
}

}  // namespace aq::editor
