// The Nuke-style edits of the document: clipboard copy and paste as graph JSON, insert after a
// node or onto a link, rename, bypass, auto-layout. Each builds the edited graph on a copy and
// records the difference as one undoable change (Document::commit_edit).
#include "document.h"

#include "canvas_view.h"

#include <algorithm>
#include <cmath>
#include <set>

namespace aq::editor {

namespace {

bool same_node(const std::optional<Node>& a, const std::optional<Node>& b) {
  if (a.has_value() != b.has_value()) return false;
  if (!a) return true;
  return a->type == b->type && a->params == b->params && a->inputs == b->inputs &&
         a->bypass == b->bypass;
}

std::string join(const std::vector<std::string>& items) {
  std::string out;
  for (const auto& item : items) out += (out.empty() ? "" : ", ") + item;
  return out;
}

bool valid_id(const std::string& id) {
  return !id.empty() && id.find('.') == std::string::npos;
}

}  // namespace

bool read_bypassed(const Graph& graph, const std::string& id) {
  auto node = graph.nodes.find(id);
  return node != graph.nodes.end() && node->second.bypass;
}

void write_bypassed(Graph& graph, const std::string& id, bool bypassed) {
  auto node = graph.nodes.find(id);
  if (node != graph.nodes.end()) node->second.bypass = bypassed;
}

void Document::apply_extras(const nlohmann::json& value) {
  if (!graph_.editor.is_object()) graph_.editor = nlohmann::json::object();
  for (const auto& [key, member] : value.items()) {
    if (member.is_null()) {
      graph_.editor.erase(key);
    } else {
      graph_.editor[key] = member;
    }
  }
  touch();
}

void Document::commit_edit(const std::string& label, const Graph& edited,
                           const std::string& coalesce_key) {
  Change change;
  change.label = label;
  change.coalesce_key = coalesce_key;
  // Editor data that belongs to no node: backdrops, reroute dots and groups.
  auto extras_of = [](const Graph& graph) {
    nlohmann::json extras = nlohmann::json::object();
    for (const char* key : {"backdrops", "reroutes", "groups"}) {
      extras[key] = graph.editor.is_object() && graph.editor.contains(key) ? graph.editor[key]
                                                                           : nlohmann::json();
    }
    return extras;
  };
  if (extras_of(graph_) != extras_of(edited)) {
    change.extras_before = extras_of(graph_);
    change.extras_after = extras_of(edited);
  }
  std::set<std::string> ids;
  for (const auto& [id, node] : graph_.nodes) ids.insert(id);
  for (const auto& [id, node] : edited.nodes) ids.insert(id);
  for (const auto& id : ids) {
    NodeState before = state_of(id);
    NodeState after;
    if (auto it = edited.nodes.find(id); it != edited.nodes.end()) after.node = it->second;
    after.position = read_position(edited, id);
    after.bypassed = read_bypassed(edited, id);
    if (same_node(before.node, after.node) && before.position == after.position &&
        before.bypassed == after.bypassed) {
      continue;
    }
    change.before[id] = before;
    change.after[id] = after;
  }
  change.output_before = graph_.output;
  change.output_after = edited.output;
  change.settings_before = graph_.settings;
  change.settings_after = edited.settings;
  commit(std::move(change));
}

std::string Document::first_input_of_type(const std::string& node_type, aq_port_type type) const {
  const NodeType* info = registry_.find(node_type);
  if (info == nullptr) return "";
  for (const auto& input : info->inputs) {
    if (input.type == type) return input.name;
  }
  return "";
}

std::string Document::copy_nodes(const std::vector<std::string>& ids) const {
  nlohmann::json nodes = nlohmann::json::object();
  nlohmann::json positions = nlohmann::json::object();
  for (const auto& id : ids) {
    auto it = graph_.nodes.find(id);
    if (it == graph_.nodes.end()) continue;
    nlohmann::json node = {{"type", it->second.type}};
    if (it->second.bypass) node["bypass"] = true;
    for (const auto& [name, value] : it->second.params) node["params"][name] = value;
    for (const auto& [port, source] : it->second.inputs) node["inputs"][port] = source.str();
    nodes[id] = node;
    if (auto at = read_position(graph_, id)) {
      positions[id] = {std::llround(at->x), std::llround(at->y)};
    }
  }
  nlohmann::json text = {{"aquarelle", graph_.version}, {"nodes", nodes}};
  if (!positions.empty()) text["editor"]["positions"] = positions;
  // A group travels with its nodes when all of them are copied.
  nlohmann::json groups = nlohmann::json::array();
  for (const Group& group : read_groups(graph_)) {
    const bool whole = std::all_of(group.nodes.begin(), group.nodes.end(), [&](const auto& id) {
      return std::find(ids.begin(), ids.end(), id) != ids.end();
    });
    if (!whole) continue;
    groups.push_back(
        {{"name", group.name},
         {"nodes", group.nodes},
         {"collapsed", group.collapsed},
         {"position", {std::llround(group.position.x), std::llround(group.position.y)}}});
  }
  if (!groups.empty()) text["editor"]["groups"] = groups;
  return text.dump(2) + "\n";
}

Result<std::vector<std::string>> Document::paste_nodes(const std::string& text,
                                                       std::optional<Position> at) {
  nlohmann::json pasted = nlohmann::json::parse(text, nullptr, /*allow_exceptions=*/false);
  if (pasted.is_discarded() || !pasted.is_object() || !pasted.contains("nodes") ||
      !pasted["nodes"].is_object() || pasted["nodes"].empty()) {
    return make_error(
        "nothing to paste: the clipboard holds no graph nodes (copy nodes in the editor, or "
        "graph JSON with a \"nodes\" object)");
  }
  Graph edited = graph_;
  std::map<std::string, std::string> new_id_of;
  for (const auto& [id, node] : pasted["nodes"].items()) {
    if (!node.is_object() || !node.contains("type") || !node["type"].is_string()) {
      return make_error("cannot paste node '" + id + "': it has no \"type\" string");
    }
    std::string type = node["type"].get<std::string>();
    std::string fresh = valid_id(id) && !edited.nodes.count(id) ? id : "";
    for (int n = 2; fresh.empty(); ++n) {
      std::string candidate = type + std::to_string(n);
      if (!edited.nodes.count(candidate)) fresh = candidate;
    }
    edited.nodes[fresh] = Node{type, {}, {}};
    new_id_of[id] = fresh;
  }
  // Where the copies go: their top-left at `at`, or offset from where they were.
  Position top_left{1e30f, 1e30f};
  auto positions = pasted.contains("editor") && pasted["editor"].is_object()
                       ? pasted["editor"].value("positions", nlohmann::json::object())
                       : nlohmann::json::object();
  for (const auto& [id, fresh] : new_id_of) {
    auto p = positions.find(id);
    if (p != positions.end() && p->is_array() && p->size() == 2 && (*p)[0].is_number() &&
        (*p)[1].is_number()) {
      top_left.x = std::min(top_left.x, (*p)[0].get<float>());
      top_left.y = std::min(top_left.y, (*p)[1].get<float>());
    }
  }
  if (top_left.x > 1e29f) top_left = Position{0, 0};
  const Position shift = at ? Position{at->x - top_left.x, at->y - top_left.y} : Position{40, 40};
  std::vector<std::string> created;
  int row = 0;
  for (const auto& [id, node] : pasted["nodes"].items()) {
    const std::string& fresh = new_id_of[id];
    Node& copy = edited.nodes[fresh];
    auto bypass = node.find("bypass");
    copy.bypass = bypass != node.end() && bypass->is_boolean() && bypass->get<bool>();
    if (node.contains("params") && node["params"].is_object()) {
      for (const auto& [name, value] : node["params"].items()) copy.params[name] = value;
    }
    if (node.contains("inputs") && node["inputs"].is_object()) {
      for (const auto& [port, source] : node["inputs"].items()) {
        if (!source.is_string()) continue;
        auto ref = PortRef::parse(source.get<std::string>());
        if (!ref) continue;
        if (auto inner = new_id_of.find(ref->node); inner != new_id_of.end()) {
          ref->node = inner->second;
        } else if (!graph_.nodes.count(ref->node)) {
          continue;  // its source is not in this graph
        }
        copy.inputs[port] = *ref;
      }
    }
    auto p = positions.find(id);
    Position where{top_left.x, top_left.y + 120.0f * row++};
    if (p != positions.end() && p->is_array() && p->size() == 2 && (*p)[0].is_number() &&
        (*p)[1].is_number()) {
      where = {(*p)[0].get<float>(), (*p)[1].get<float>()};
    }
    write_position(edited, fresh, Position{where.x + shift.x, where.y + shift.y});
    created.push_back(fresh);
  }
  // Groups copied whole come back around the pasted nodes, under a name not yet taken.
  Graph copied;
  copied.editor = pasted.value("editor", nlohmann::json::object());
  for (const auto& [id, node] : pasted["nodes"].items()) copied.nodes[id] = Node{};
  auto groups = read_groups(edited);
  const size_t before = groups.size();
  for (Group group : read_groups(copied)) {
    for (auto& id : group.nodes) id = new_id_of[id];
    const std::string base = group.name;
    for (int n = 2; std::any_of(groups.begin(), groups.end(),
                                [&](const Group& g) { return g.name == group.name; });
         ++n) {
      group.name = base + std::to_string(n);
    }
    group.position = {group.position.x + shift.x, group.position.y + shift.y};
    groups.push_back(std::move(group));
  }
  if (groups.size() > before) write_groups(edited, groups);
  commit_edit(created.size() == 1 ? "paste " + created.front()
                                  : "paste " + std::to_string(created.size()) + " nodes",
              edited);
  return created;
}

Result<std::string> Document::insert_node(
    const std::string& type, Position at, const PortRef& after,
    const std::optional<std::pair<std::string, std::string>>& only_link) {
  auto source = graph_.nodes.find(after.node);
  if (source == graph_.nodes.end()) {
    return make_error("cannot insert after '" + after.node + "': no such node");
  }
  const NodeType* source_type = registry_.find(source->second.type);
  const PortInfo* port = source_type ? source_type->output(after.port) : nullptr;
  if (port == nullptr) {
    return make_error("cannot insert after " + after.str() + ": no such output");
  }
  const NodeType* new_type = registry_.find(type);
  if (new_type == nullptr) {
    return make_error("cannot add a node of type '" + type +
                      "': no installed plugin provides it (installed: " + join(registry_.names()) +
                      ")");
  }
  const std::string input = first_input_of_type(type, port->type);
  if (input.empty()) {
    return make_error("cannot insert a '" + type + "' after " + after.str() +
                      ": it has no input of that output's type; add it with nothing selected "
                      "and link it by hand");
  }
  Graph edited = graph_;
  const std::string id = free_id(type);
  const PortInfo* new_output = nullptr;
  for (const auto& output : new_type->outputs) {
    if (output.type == port->type && new_output == nullptr) new_output = &output;
  }
  if (new_output != nullptr) {
    const PortRef through{id, new_output->name};
    for (auto& [other, node] : edited.nodes) {
      for (auto& [in, from] : node.inputs) {
        const bool chosen = !only_link || (only_link->first == other && only_link->second == in);
        if (from == after && chosen) from = through;
      }
    }
    if (!only_link && edited.output == after) edited.output = through;
  }
  edited.nodes[id] = Node{type, {}, {{input, after}}};
  write_position(edited, id, at);
  commit_edit("insert " + id +
                  (only_link ? " on the link into " + only_link->first + "." + only_link->second
                             : " after " + after.node),
              edited);
  return id;
}

Result<std::string> Document::insert_node_after(const std::string& type, Position at,
                                                const PortRef& after) {
  return insert_node(type, at, after, std::nullopt);
}

Result<std::string> Document::insert_node_on_link(const std::string& type, Position at,
                                                  const std::string& to_node,
                                                  const std::string& to_input) {
  auto target = graph_.nodes.find(to_node);
  if (target == graph_.nodes.end() || !target->second.inputs.count(to_input)) {
    return make_error("cannot insert on the link into " + to_node + "." + to_input +
                      ": there is no such link");
  }
  return insert_node(type, at, target->second.inputs.at(to_input),
                     std::make_pair(to_node, to_input));
}

Status Document::splice_into_link(const std::string& id, const std::string& to_node,
                                  const std::string& to_input) {
  auto node = graph_.nodes.find(id);
  auto target = graph_.nodes.find(to_node);
  if (node == graph_.nodes.end() || target == graph_.nodes.end() ||
      !target->second.inputs.count(to_input)) {
    return make_error("cannot drop '" + id + "' on the link into " + to_node + "." + to_input +
                      ": there is no such link");
  }
  const PortRef source = target->second.inputs.at(to_input);
  if (source.node == id || to_node == id) return make_error("'" + id + "' is on that link already");
  const NodeType* type = registry_.find(node->second.type);
  const NodeType* source_type = nullptr;
  if (auto from = graph_.nodes.find(source.node); from != graph_.nodes.end()) {
    source_type = registry_.find(from->second.type);
  }
  const PortInfo* port = source_type ? source_type->output(source.port) : nullptr;
  if (type == nullptr || port == nullptr) {
    return make_error("cannot drop '" + id + "' on that link: its types are unknown");
  }
  const std::string input = first_input_of_type(node->second.type, port->type);
  const PortInfo* output = nullptr;
  for (const auto& candidate : type->outputs) {
    if (candidate.type == port->type && output == nullptr) output = &candidate;
  }
  if (input.empty() || output == nullptr) {
    return make_error("cannot drop '" + id + "' on the link into " + to_node + "." + to_input +
                      ": it has no input and output of that link's type");
  }
  Graph edited = graph_;
  edited.nodes.at(id).inputs[input] = source;
  edited.nodes.at(to_node).inputs[to_input] = PortRef{id, output->name};
  std::string why = why_not_link(source, id, input);
  if (!why.empty()) return make_error("cannot drop '" + id + "' on that link: " + why);
  commit_edit("drop " + id + " on the link into " + to_node + "." + to_input, edited);
  return Ok{};
}

Status Document::rename_node(const std::string& id, const std::string& new_id) {
  if (!graph_.nodes.count(id)) return make_error("cannot rename '" + id + "': no such node");
  if (new_id == id) return Ok{};
  if (!valid_id(new_id)) {
    return make_error("cannot rename '" + id + "' to '" + new_id +
                      "': an id must be non-empty and have no '.'");
  }
  if (graph_.nodes.count(new_id)) {
    return make_error("cannot rename '" + id + "' to '" + new_id +
                      "': that id is taken; choose another");
  }
  Graph edited = graph_;
  edited.nodes[new_id] = edited.nodes.at(id);
  edited.nodes.erase(id);
  for (auto& [other, node] : edited.nodes) {
    for (auto& [in, from] : node.inputs) {
      if (from.node == id) from.node = new_id;
    }
  }
  if (edited.output && edited.output->node == id) edited.output->node = new_id;
  write_position(edited, new_id, read_position(graph_, id));
  write_position(edited, id, std::nullopt);
  auto groups = read_groups(graph_);
  for (auto& group : groups) std::replace(group.nodes.begin(), group.nodes.end(), id, new_id);
  if (!groups.empty()) write_groups(edited, groups);
  commit_edit("rename " + id + " to " + new_id, edited);
  return Ok{};
}

Status Document::set_bypassed(const std::vector<std::string>& ids, bool bypassed) {
  if (ids.empty()) return make_error("nothing to bypass: select nodes first");
  Graph edited = graph_;
  for (const auto& id : ids) {
    if (!graph_.nodes.count(id)) return make_error("cannot bypass '" + id + "': no such node");
    write_bypassed(edited, id, bypassed);
  }
  commit_edit(std::string(bypassed ? "bypass " : "enable ") +
                  (ids.size() == 1 ? ids.front() : std::to_string(ids.size()) + " nodes"),
              edited);
  return Ok{};
}

bool Document::bypassed(const std::string& id) const {
  return read_bypassed(graph_, id);
}

std::vector<Backdrop> read_backdrops(const Graph& graph) {
  std::vector<Backdrop> out;
  if (!graph.editor.is_object() || !graph.editor.contains("backdrops")) return out;
  const auto& list = graph.editor["backdrops"];
  if (!list.is_array()) return out;
  for (const auto& item : list) {
    if (!item.is_object() || !item.contains("rect") || !item["rect"].is_array() ||
        item["rect"].size() != 4) {
      continue;
    }
    const auto& r = item["rect"];
    if (!std::all_of(r.begin(), r.end(), [](const auto& v) { return v.is_number(); })) continue;
    Backdrop backdrop;
    backdrop.label = item.value("label", std::string());
    backdrop.at = {r[0].get<float>(), r[1].get<float>()};
    backdrop.width = r[2].get<float>();
    backdrop.height = r[3].get<float>();
    out.push_back(backdrop);
  }
  return out;
}

void write_backdrops(Graph& graph, const std::vector<Backdrop>& backdrops) {
  if (!graph.editor.is_object()) graph.editor = nlohmann::json::object();
  if (backdrops.empty()) {
    graph.editor.erase("backdrops");
    return;
  }
  nlohmann::json list = nlohmann::json::array();
  for (const auto& b : backdrops) {
    list.push_back({{"label", b.label},
                    {"rect",
                     {std::llround(b.at.x), std::llround(b.at.y), std::llround(b.width),
                      std::llround(b.height)}}});
  }
  graph.editor["backdrops"] = list;
}

Result<size_t> Document::add_backdrop(const std::vector<std::string>& around,
                                      const std::string& label) {
  constexpr float kMargin = 30.0f;
  constexpr float kTitle = 36.0f;
  Rect box{{1e30f, 1e30f}, {-1e30f, -1e30f}};
  for (const auto& id : around) {
    if (!graph_.nodes.count(id)) return make_error("cannot frame '" + id + "': no such node");
    Rect r = node_rect(graph_, registry_, id);
    box.min = {std::min(box.min.x, r.min.x), std::min(box.min.y, r.min.y)};
    box.max = {std::max(box.max.x, r.max.x), std::max(box.max.y, r.max.y)};
  }
  if (around.empty()) return make_error("nothing to frame: select the nodes for the backdrop");
  Graph edited = graph_;
  auto backdrops = read_backdrops(edited);
  backdrops.push_back({label.empty() ? "Backdrop" : label,
                       {box.min.x - kMargin, box.min.y - kMargin - kTitle},
                       box.max.x - box.min.x + 2 * kMargin,
                       box.max.y - box.min.y + 2 * kMargin + kTitle});
  write_backdrops(edited, backdrops);
  commit_edit("backdrop " + backdrops.back().label, edited);
  return backdrops.size() - 1;
}

Status Document::set_backdrop_label(size_t index, const std::string& label) {
  Graph edited = graph_;
  auto backdrops = read_backdrops(edited);
  if (index >= backdrops.size()) return make_error("no backdrop " + std::to_string(index));
  backdrops[index].label = label;
  write_backdrops(edited, backdrops);
  commit_edit("label backdrop " + label, edited);
  return Ok{};
}

Status Document::remove_backdrop(size_t index) {
  Graph edited = graph_;
  auto backdrops = read_backdrops(edited);
  if (index >= backdrops.size()) return make_error("no backdrop " + std::to_string(index));
  backdrops.erase(backdrops.begin() + static_cast<long>(index));
  write_backdrops(edited, backdrops);
  commit_edit("delete backdrop", edited);
  return Ok{};
}

Status Document::move_backdrop(size_t index, Position by, const std::string& coalesce_key) {
  Graph edited = graph_;
  auto backdrops = read_backdrops(edited);
  if (index >= backdrops.size()) return make_error("no backdrop " + std::to_string(index));
  Backdrop& moved = backdrops[index];
  // The nodes inside it travel with it (Nuke's backdrops).
  for (const auto& [id, node] : graph_.nodes) {
    Position at = node_position(graph_, id);
    if (moved.contains(at)) write_position(edited, id, Position{at.x + by.x, at.y + by.y});
  }
  moved.at = {moved.at.x + by.x, moved.at.y + by.y};
  write_backdrops(edited, backdrops);
  commit_edit("move backdrop " + moved.label, edited, coalesce_key);
  return Ok{};
}

std::vector<Position> read_reroutes(const Graph& graph, const std::string& node,
                                    const std::string& input) {
  std::vector<Position> dots;
  auto target = graph.nodes.find(node);
  if (target == graph.nodes.end() || !target->second.inputs.count(input)) return dots;
  if (!graph.editor.is_object() || !graph.editor.contains("reroutes")) return dots;
  const auto& all = graph.editor["reroutes"];
  auto it = all.is_object() ? all.find(node + "." + input) : all.end();
  if (it == all.end() || !it->is_object()) return dots;
  // Dots drawn for a link that has since been relinked elsewhere are ignored.
  if (it->value("from", std::string()) != target->second.inputs.at(input).str()) return dots;
  for (const auto& dot : it->value("dots", nlohmann::json::array())) {
    if (dot.is_array() && dot.size() == 2 && dot[0].is_number() && dot[1].is_number()) {
      dots.push_back({dot[0].get<float>(), dot[1].get<float>()});
    }
  }
  return dots;
}

void write_reroutes(Graph& graph, const std::string& node, const std::string& input,
                    const std::vector<Position>& dots) {
  if (!graph.editor.is_object()) graph.editor = nlohmann::json::object();
  nlohmann::json& all = graph.editor["reroutes"];
  if (!all.is_object()) all = nlohmann::json::object();
  const std::string key = node + "." + input;
  if (dots.empty()) {
    all.erase(key);
  } else {
    nlohmann::json list = nlohmann::json::array();
    for (const auto& dot : dots) list.push_back({std::llround(dot.x), std::llround(dot.y)});
    all[key] = {{"from", graph.nodes.at(node).inputs.at(input).str()}, {"dots", list}};
  }
  if (all.empty()) graph.editor.erase("reroutes");
}

Status Document::add_reroute(const std::string& node, const std::string& input, Position at) {
  auto target = graph_.nodes.find(node);
  if (target == graph_.nodes.end() || !target->second.inputs.count(input)) {
    return make_error("cannot add a dot to the link into " + node + "." + input +
                      ": there is no such link");
  }
  Graph edited = graph_;
  auto dots = read_reroutes(graph_, node, input);
  // Keep the dots in order along the link: from the source's end, by x.
  dots.push_back(at);
  std::stable_sort(dots.begin(), dots.end(),
                   [](const Position& a, const Position& b) { return a.x < b.x; });
  write_reroutes(edited, node, input, dots);
  commit_edit("dot on the link into " + node + "." + input, edited);
  return Ok{};
}

Status Document::move_reroute(const std::string& node, const std::string& input, size_t index,
                              Position to, const std::string& coalesce_key) {
  auto dots = read_reroutes(graph_, node, input);
  if (index >= dots.size()) return make_error("no such dot on the link into " + node + "." + input);
  Graph edited = graph_;
  dots[index] = to;
  write_reroutes(edited, node, input, dots);
  commit_edit("move a dot", edited, coalesce_key);
  return Ok{};
}

Status Document::remove_reroute(const std::string& node, const std::string& input, size_t index) {
  auto dots = read_reroutes(graph_, node, input);
  if (index >= dots.size()) return make_error("no such dot on the link into " + node + "." + input);
  Graph edited = graph_;
  dots.erase(dots.begin() + static_cast<long>(index));
  write_reroutes(edited, node, input, dots);
  commit_edit("remove a dot", edited);
  return Ok{};
}

Status Document::auto_layout() {
  if (graph_.nodes.empty()) return make_error("nothing to lay out: the graph is empty");
  Graph edited = graph_;
  for (const auto& [id, at] : automatic_positions(graph_, &registry_))
    write_position(edited, id, at);
  // Collapsed groups go where their nodes went.
  auto groups = read_groups(edited);
  for (auto& group : groups) group.position = members_top_left(edited, registry_, group.nodes);
  if (!groups.empty()) write_groups(edited, groups);
  commit_edit("auto-layout", edited);
  return Ok{};
}

}  // namespace aq::editor
