// The editor's actions: document edits plus the selection, viewer and status-line bookkeeping
// that goes with each.
#include "editor_actions.h"

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <set>

namespace aq::editor {

std::optional<PortRef> EditorState::shown_output() const {
  if (viewed) {
    auto it = doc.graph().nodes.find(viewed->node);
    if (it != doc.graph().nodes.end()) return viewed;
  }
  return doc.graph().output;
}

namespace actions {

namespace {

// The selection and viewed output may name nodes an undo just removed.
bool exists(const EditorState& state, const std::string& id) {
  if (auto name = group_name_of_item(id)) {
    for (const auto& group : read_groups(state.doc.graph())) {
      if (group.name == *name && group.collapsed) return true;
    }
    return false;
  }
  return state.doc.graph().nodes.count(id) > 0;
}

// The selected nodes, a selected collapsed group standing for its members.
std::vector<std::string> selected_nodes(const EditorState& state) {
  return expand_group_items(state.doc.graph(), {state.selection.begin(), state.selection.end()});
}

void forget_missing(EditorState& state) {
  std::erase_if(state.selection, [&](const std::string& id) { return !exists(state, id); });
  if (state.viewed && !state.doc.graph().nodes.count(state.viewed->node)) state.viewed.reset();
  if (state.compare && !state.doc.graph().nodes.count(state.compare->node)) state.compare.reset();
}

}  // namespace

void report(EditorState& state, const Status& status, const std::string& success) {
  if (status.ok()) {
    state.status = success;
    state.status_is_error = false;
  } else {
    state.status = status.message();
    state.status_is_error = true;
    ++state.refused_count;
  }
}

Result<std::string> add_node(EditorState& state, const std::string& type, Position at,
                             const std::string& wanted_id) {
  auto added = state.doc.add_node(type, at, wanted_id);
  if (added) {
    state.selection = {*added};
    report(state, Ok{}, "added " + *added);
  } else {
    report(state, added.error(), "");
  }
  return added;
}

Status link(EditorState& state, const PortRef& from, const std::string& to_node,
            const std::string& to_input) {
  Status linked = state.doc.link(from, to_node, to_input);
  report(state, linked, "linked " + from.str() + " -> " + to_node + "." + to_input);
  return linked;
}

Status unlink(EditorState& state, const std::string& node, const std::string& input) {
  Status unlinked = state.doc.unlink(node, input);
  report(state, unlinked, "unlinked " + node + "." + input);
  return unlinked;
}

Status move(EditorState& state, const std::map<std::string, Position>& positions, bool gesture) {
  Status moved = state.doc.move_nodes(positions, gesture ? "move" : "");
  const auto& [first_id, first_at] = *positions.begin();
  report(
      state, moved,
      "moved " + first_id + " to (" + std::to_string(static_cast<int>(first_at.x)) + ", " +
          std::to_string(static_cast<int>(first_at.y)) + ")" +
          (positions.size() > 1 ? " and " + std::to_string(positions.size() - 1) + " more" : ""));
  return moved;
}

Status set_param(EditorState& state, const std::string& node, const std::string& param,
                 const nlohmann::json& value, bool gesture) {
  Status set =
      state.doc.set_param(node, param, value, gesture ? "param:" + node + "." + param : "");
  // The value as stored (the shortest decimal of a slider's float), not as the widget held it.
  nlohmann::json shown = value;
  if (auto it = state.doc.graph().nodes.find(node); set && it != state.doc.graph().nodes.end()) {
    if (auto stored = it->second.params.find(param); stored != it->second.params.end()) {
      shown = stored->second;
    }
  }
  report(state, set,
         value.is_null() ? node + "." + param + " reset to its default"
                         : node + "." + param + " = " + shown.dump());
  return set;
}

void end_gesture(EditorState& state) {
  state.doc.end_gesture();
}

Status delete_nodes(EditorState& state, const std::vector<std::string>& ids) {
  Status removed = state.doc.remove_nodes(ids);
  report(state, removed, "deleted " + std::to_string(ids.size()) + " node(s)");
  forget_missing(state);
  return removed;
}

Status delete_selection(EditorState& state) {
  // Del reconnects the chain around what it deletes (Nuke, Blender).
  const std::vector<std::string> ids = selected_nodes(state);
  Status removed = state.doc.remove_nodes(ids, /*reconnect=*/true);
  report(state, removed, "deleted " + std::to_string(ids.size()) + " node(s), chain reconnected");
  forget_missing(state);
  return removed;
}

Status duplicate_selection(EditorState& state) {
  // Copies go below the originals, clear of them (Nuke offsets them; overlapping hides them).
  const Graph& graph = state.doc.graph();
  float top = 1e30f;
  float bottom = -1e30f;
  for (const auto& id : selected_nodes(state)) {
    auto node = graph.nodes.find(id);
    if (node == graph.nodes.end()) continue;
    Rect rect = node_rect(graph, state.doc.registry(), id);
    top = std::min(top, rect.min.y);
    bottom = std::max(bottom, rect.max.y);
  }
  const Position offset = clear_offset(graph, state.doc.registry(), selected_nodes(state),
                                       {30.0f, bottom > top ? bottom - top + 30.0f : 40.0f});
  auto copies = state.doc.duplicate_nodes(selected_nodes(state), offset);
  if (!copies) {
    report(state, copies.error(), "");
    return copies.error();
  }
  state.selection = {copies->begin(), copies->end()};
  report(state, Ok{}, "duplicated into " + std::to_string(copies->size()) + " new node(s)");
  return Ok{};
}

void select(EditorState& state, const std::vector<std::string>& ids, bool add) {
  if (!add) state.selection.clear();
  for (const auto& id : ids) {
    if (exists(state, id)) state.selection.insert(id);
  }
  state.status = std::to_string(state.selection.size()) + " node(s) selected";
  state.status_is_error = false;
}

void clear_selection(EditorState& state) {
  state.selection.clear();
  if (state.status.ends_with("selected")) state.status.clear();
}

Result<std::string> add_node_at_cursor(EditorState& state, const std::string& type, Position at) {
  const Graph& graph = state.doc.graph();
  at = free_spot(graph, state.doc.registry(), type, at);
  if (state.selection.size() == 1) {
    std::optional<PortRef> from;
    const std::string after = *state.selection.begin();
    if (auto name = group_name_of_item(after)) {
      // After a collapsed group: after its first output.
      for (const auto& group : read_groups(graph)) {
        if (group.name != *name) continue;
        const GroupPorts ports = group_ports(graph, state.doc.registry(), group);
        if (!ports.outputs.empty()) from = ports.outputs.front().inner;
      }
    } else if (auto node = graph.nodes.find(after); node != graph.nodes.end()) {
      const NodeType* after_type = state.doc.registry().find(node->second.type);
      if (after_type != nullptr && !after_type->outputs.empty()) {
        from = PortRef{after, after_type->outputs.front().name};
      }
    }
    if (from) {
      auto inserted = state.doc.insert_node_after(type, at, *from);
      if (inserted) {
        state.selection = {*inserted};
        report(state, Ok{}, "inserted " + *inserted + " after " + after);
        return inserted;
      }
      // A node that cannot take the selected output is added unlinked, as without selection.
    }
  }
  return add_node(state, type, at);
}

Result<std::string> insert_on_link(EditorState& state, const std::string& type, Position at,
                                   const std::string& to_node, const std::string& to_input) {
  at = free_spot(state.doc.graph(), state.doc.registry(), type, at);  // never on another node
  auto inserted = state.doc.insert_node_on_link(type, at, to_node, to_input);
  if (inserted) {
    state.selection = {*inserted};
    report(state, Ok{}, "inserted " + *inserted + " on the link into " + to_node + "." + to_input);
  } else {
    report(state, inserted.error(), "");
  }
  return inserted;
}

Result<std::vector<std::string>> drop_files(EditorState& state,
                                            const std::vector<std::string>& paths, Position at) {
  namespace fs = std::filesystem;
  std::vector<std::string> added;
  std::string skipped;
  for (const std::string& path : paths) {
    std::string extension = fs::path(path).extension().string();
    for (char& c : extension) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    static const std::set<std::string> kImages = {".png",  ".jpg", ".jpeg", ".exr", ".tif",
                                                  ".tiff", ".hdr", ".bmp",  ".tga"};
    if (!kImages.count(extension)) {
      skipped += (skipped.empty() ? "" : ", ") + fs::path(path).filename().string();
      continue;
    }
    std::string stored = path;
    if (!state.doc.path().empty()) {  // relative to the graph's folder when under it
      std::error_code error;
      const fs::path base = fs::absolute(state.doc.path(), error).parent_path();
      const fs::path relative = fs::relative(fs::absolute(path, error), base, error);
      if (!error && !relative.empty() && relative.string().rfind("..", 0) != 0) {
        stored = relative.string();
      }
    }
    const Position spot = free_spot(state.doc.graph(), state.doc.registry(), "read", at);
    auto id = state.doc.add_node("read", spot);
    if (!id) {
      report(state, id.error(), "");
      return id.error();
    }
    (void)state.doc.set_param(*id, "path", stored);
    added.push_back(*id);
  }
  if (added.empty()) {
    const Error none = make_error("nothing to add: " + (skipped.empty() ? "no files" : skipped) +
                                  " (drop image files: png, jpg, exr, tif, hdr, bmp, tga)");
    report(state, none, "");
    return none;
  }
  state.selection = {added.begin(), added.end()};
  report(state, Ok{},
         "added " + std::to_string(added.size()) + " read node(s)" +
             (skipped.empty() ? "" : "; not images: " + skipped));
  return added;
}

std::string copy_selection(EditorState& state) {
  if (state.selection.empty()) {
    report(state, make_error("nothing to copy: select nodes first"), "");
    return "";
  }
  report(state, Ok{}, "copied " + std::to_string(state.selection.size()) + " node(s)");
  return state.doc.copy_nodes(selected_nodes(state));
}

Status paste(EditorState& state, const std::string& text, std::optional<Position> at) {
  auto pasted = state.doc.paste_nodes(text, at);
  if (!pasted) {
    report(state, pasted.error(), "");
    return pasted.error();
  }
  state.selection = {pasted->begin(), pasted->end()};
  report(state, Ok{}, "pasted " + std::to_string(pasted->size()) + " node(s)");
  return Ok{};
}

Status rename(EditorState& state, const std::string& id, const std::string& new_id) {
  if (auto group = group_name_of_item(id)) {
    Status renamed = state.doc.rename_group(*group, new_id);
    if (renamed && state.selection.erase(id)) state.selection.insert(group_item_id(new_id));
    report(state, renamed, "renamed group " + *group + " to " + new_id);
    return renamed;
  }
  Status renamed = state.doc.rename_node(id, new_id);
  if (renamed && state.selection.erase(id)) state.selection.insert(new_id);
  if (renamed && state.viewed && state.viewed->node == id) state.viewed->node = new_id;
  report(state, renamed, "renamed " + id + " to " + new_id);
  return renamed;
}

Status toggle_bypass(EditorState& state) {
  std::vector<std::string> ids = selected_nodes(state);
  const bool all = !ids.empty() && std::all_of(ids.begin(), ids.end(), [&](const auto& id) {
    return state.doc.bypassed(id);
  });
  Status done = state.doc.set_bypassed(ids, !all);
  report(state, done, (all ? "enabled " : "bypassed ") + std::to_string(ids.size()) + " node(s)");
  return done;
}

Status backdrop_around_selection(EditorState& state, const std::string& label) {
  auto added = state.doc.add_backdrop(selected_nodes(state), label);
  report(state, added ? Status(Ok{}) : Status(added.error()), "backdrop '" + label + "' added");
  return added ? Status(Ok{}) : Status(added.error());
}

Status group_selection(EditorState& state) {
  const std::vector<std::string> nodes = selected_nodes(state);
  // The nodes of one expanded group, selected: Ctrl+G collapses it again.
  for (const auto& group : read_groups(state.doc.graph())) {
    if (group.collapsed || nodes.empty()) continue;
    if (std::all_of(nodes.begin(), nodes.end(), [&](const std::string& id) {
          return std::find(group.nodes.begin(), group.nodes.end(), id) != group.nodes.end();
        })) {
      return set_group_collapsed(state, group.name, true);
    }
  }
  auto grouped = state.doc.group_nodes(nodes);
  if (!grouped) {
    report(state, grouped.error(), "");
    return grouped.error();
  }
  state.selection = {group_item_id(*grouped)};
  report(state, Ok{}, "grouped " + std::to_string(nodes.size()) + " node(s) as " + *grouped);
  return Ok{};
}

Status ungroup_selection(EditorState& state) {
  std::set<std::string> names;
  const std::vector<std::string> nodes = selected_nodes(state);
  for (const auto& group : read_groups(state.doc.graph())) {
    for (const auto& id : nodes) {
      if (std::find(group.nodes.begin(), group.nodes.end(), id) != group.nodes.end()) {
        names.insert(group.name);
      }
    }
  }
  if (names.empty()) {
    Status none = make_error("nothing to ungroup: select a group or nodes in one");
    report(state, none, "");
    return none;
  }
  for (const auto& name : names) {
    Status done = state.doc.ungroup(name);
    if (!done) {
      report(state, done, "");
      return done;
    }
  }
  state.selection = {nodes.begin(), nodes.end()};
  report(state, Ok{}, "ungrouped " + std::to_string(names.size()) + " group(s)");
  return Ok{};
}

Status set_group_collapsed(EditorState& state, const std::string& name, bool collapsed) {
  std::vector<std::string> members;
  for (const auto& group : read_groups(state.doc.graph())) {
    if (group.name == name) members = group.nodes;
  }
  Status done = state.doc.set_group_collapsed(name, collapsed);
  if (done) {
    if (collapsed) {
      state.selection = {group_item_id(name)};
    } else {
      state.selection = {members.begin(), members.end()};
    }
  }
  report(state, done, (collapsed ? "collapsed " : "expanded ") + name);
  forget_missing(state);
  return done;
}

Status compare_with(EditorState& state, const std::optional<PortRef>& output) {
  if (!output) {
    state.compare.reset();
    report(state, Ok{}, "compare off");
    return Ok{};
  }
  auto node = state.doc.graph().nodes.find(output->node);
  const NodeType* type = node != state.doc.graph().nodes.end()
                             ? state.doc.registry().find(node->second.type)
                             : nullptr;
  if (type == nullptr || type->output(output->port) == nullptr) {
    Status refused = make_error("cannot compare with " + output->str() +
                                ": no such node output (pick one of the graph's outputs)");
    report(state, refused, "");
    return refused;
  }
  state.compare = output;
  const auto shown = state.shown_output();
  report(state, Ok{},
         "compare A " + (shown ? shown->str() : std::string("(none)")) + " | B " + output->str());
  return Ok{};
}

Status auto_layout(EditorState& state) {
  Status done = state.doc.auto_layout();
  report(state, done, "laid out " + std::to_string(state.doc.graph().nodes.size()) + " nodes");
  return done;
}

Status select_output(EditorState& state, const PortRef& output) {
  auto node = state.doc.graph().nodes.find(output.node);
  Status checked = Ok{};
  if (node == state.doc.graph().nodes.end()) {
    checked =
        make_error("cannot view " + output.str() + ": there is no node '" + output.node + "'");
  } else if (const NodeType* type = state.doc.registry().find(node->second.type);
             type != nullptr && type->output(output.port) == nullptr) {
    checked = make_error("cannot view " + output.str() + ": '" + type->name + "' has no output '" +
                         output.port + "'");
  }
  if (checked) state.viewed = output;
  report(state, checked, "viewing " + output.str());
  return checked;
}

void cycle_output(EditorState& state, int step) {
  std::vector<PortRef> all;
  for (const auto& [id, node] : state.doc.graph().nodes) {
    if (const NodeType* type = state.doc.registry().find(node.type)) {
      for (const auto& port : type->outputs) all.push_back({id, port.name});
    }
  }
  if (all.empty()) return;
  auto shown = state.shown_output();
  auto it = shown ? std::find(all.begin(), all.end(), *shown) : all.end();
  long index = it == all.end() ? 0 : (it - all.begin()) + step;
  long count = static_cast<long>(all.size());
  index = ((index % count) + count) % count;
  (void)select_output(state, all[index]);
}

Status set_graph_output(EditorState& state, const PortRef& output) {
  Status set = state.doc.set_output(output);
  report(state, set, "graph output is now " + output.str());
  return set;
}

bool undo(EditorState& state) {
  std::string label = state.doc.undo_label();
  bool done = state.doc.undo();
  forget_missing(state);
  report(state, done ? Status(Ok{}) : Status(make_error("nothing to undo")), "undid " + label);
  return done;
}

bool redo(EditorState& state) {
  std::string label = state.doc.redo_label();
  bool done = state.doc.redo();
  forget_missing(state);
  report(state, done ? Status(Ok{}) : Status(make_error("nothing to redo")), "redid " + label);
  return done;
}

Status save(EditorState& state) {
  Status saved = state.doc.save();
  report(state, saved, "saved " + state.doc.path());
  return saved;
}

Status save_as(EditorState& state, const std::string& path, bool replace) {
  Status saved = state.doc.save_as(path, replace);
  report(state, saved, "saved " + path);
  return saved;
}

Status open(EditorState& state, const std::string& path) {
  Status opened = state.doc.open(path);
  if (opened) {
    state.selection.clear();
    state.viewed.reset();
    state.compare.reset();
    state.frame = state.doc.graph().settings.first_frame;
  }
  report(state, opened, "opened " + path);
  return opened;
}

void new_graph(EditorState& state) {
  state.doc.new_graph();
  state.selection.clear();
  state.viewed.reset();
  state.compare.reset();
  report(state, Ok{}, "new graph");
}

void set_frame(EditorState& state, int frame) {
  const Settings& settings = state.doc.graph().settings;
  state.frame =
      std::clamp(frame, settings.first_frame, std::max(settings.first_frame, settings.last_frame));
}

}  // namespace actions
}  // namespace aq::editor
