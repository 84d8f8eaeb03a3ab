// The editor's document: edits as recorded changes, undo/redo, files and autosave. See
// document.h for the shape of a change.
#include "document.h"

#include "canvas_view.h"

#include <aquarelle/core/message_text.h>
#include <aquarelle/core/write_guard.h>
#include <aquarelle/sdk/regular_file.hpp>

#include <algorithm>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <set>
#include <sstream>
#include <system_error>

namespace aq::editor {

namespace fs = std::filesystem;

namespace {

bool is_number(const nlohmann::json& v) {
  return v.is_number();
}

bool in_range(const ParamInfo& param, double v) {
  if (!(param.max_value > param.min_value)) return true;  // no declared range
  return v >= param.min_value && v <= param.max_value;
}

std::string range_text(const ParamInfo& param) {
  std::ostringstream out;
  out << "[" << param.min_value << ", " << param.max_value << "]";
  return out.str();
}

std::string join(const std::vector<std::string>& items) {
  std::string out;
  for (const auto& item : items) out += (out.empty() ? "" : ", ") + item;
  return out;
}

}  // namespace

// ---- Positions ---------------------------------------------------------------------------

std::optional<Position> read_position(const Graph& graph, const std::string& id) {
  if (!graph.editor.is_object()) return std::nullopt;
  auto positions = graph.editor.find("positions");
  if (positions == graph.editor.end() || !positions->is_object()) return std::nullopt;
  auto it = positions->find(id);
  if (it == positions->end() || !it->is_array() || it->size() != 2 || !(*it)[0].is_number() ||
      !(*it)[1].is_number()) {
    return std::nullopt;
  }
  return Position{(*it)[0].get<float>(), (*it)[1].get<float>()};
}

void write_position(Graph& graph, const std::string& id, const std::optional<Position>& position) {
  if (!graph.editor.is_object()) graph.editor = nlohmann::json::object();
  nlohmann::json& positions = graph.editor["positions"];
  if (!positions.is_object()) positions = nlohmann::json::object();
  if (position) {
    // Whole canvas units, written as integers, keep the saved file short and diffs quiet.
    positions[id] = {std::llround(position->x), std::llround(position->y)};
  } else {
    positions.erase(id);
  }
}

std::string why_bad_param_value(const ParamInfo& param, const nlohmann::json& value) {
  const std::string what = "parameter '" + param.name + "' (" + param_type_name(param.type) + ")";
  switch (param.type) {
    case AQ_PARAM_FLOAT:
      if (!is_number(value)) return what + " needs a number, got " + value.dump();
      if (!std::isfinite(value.get<double>())) return what + " needs a finite number";
      if (!in_range(param, value.get<double>())) {
        return what + " = " + value.dump() + " is outside its range " + range_text(param);
      }
      return "";
    case AQ_PARAM_INT: {
      if (!value.is_number_integer()) {
        bool whole = value.is_number() && std::floor(value.get<double>()) == value.get<double>();
        if (!whole) return what + " needs a whole number, got " + value.dump();
      }
      if (!in_range(param, value.get<double>())) {
        return what + " = " + value.dump() + " is outside its range " + range_text(param);
      }
      return "";
    }
    case AQ_PARAM_BOOL:
      return value.is_boolean() ? "" : what + " needs true or false, got " + value.dump();
    case AQ_PARAM_ENUM: {
      if (!value.is_string()) {
        return what + " needs one of " + join(param.enum_values) + ", got " + value.dump();
      }
      auto name = value.get<std::string>();
      if (std::find(param.enum_values.begin(), param.enum_values.end(), name) ==
          param.enum_values.end()) {
        return what + ": '" + name + "' is not one of " + join(param.enum_values);
      }
      return "";
    }
    case AQ_PARAM_STRING:
    case AQ_PARAM_PATH:
      return value.is_string() ? "" : what + " needs a string, got " + value.dump();
    case AQ_PARAM_COLOR:
    case AQ_PARAM_VEC3: {
      if (!value.is_array() || value.size() != 3 || !is_number(value[0]) || !is_number(value[1]) ||
          !is_number(value[2])) {
        return what + " needs three numbers [x, y, z], got " + value.dump();
      }
      for (const auto& component : value) {
        // Colours may go past 1 (HDR); only vectors hold to their declared range.
        if (param.type == AQ_PARAM_VEC3 && !in_range(param, component.get<double>())) {
          return what + " component " + component.dump() + " is outside its range " +
                 range_text(param);
        }
        if (!std::isfinite(component.get<double>())) return what + " needs finite numbers";
      }
      return "";
    }
  }
  return what + " has a type the editor does not know";
}

std::map<std::string, Position> automatic_positions(const Graph& graph, const Registry* registry) {
  constexpr float kColumnStep = 230.0f;
  float kRowStep = 180.0f;  // fits a node with six ports
  if (registry != nullptr) {
    for (const auto& [id, node] : graph.nodes) {
      if (const NodeType* type = registry->find(node.type)) {
        const size_t rows = std::max(type->inputs.size(), type->outputs.size());
        kRowStep = std::max(kRowStep, NodeMetrics::kHeader + rows * NodeMetrics::kRow +
                                          NodeMetrics::kFooter + 30.0f);
      }
    }
  }
  // Column = longest path from a source, so the layout flows left to right.
  std::map<std::string, int> depth;
  std::set<std::string> visiting;
  std::function<int(const std::string&)> visit = [&](const std::string& id) -> int {
    auto known = depth.find(id);
    if (known != depth.end()) return known->second;
    auto node = graph.nodes.find(id);
    if (node == graph.nodes.end() || visiting.count(id)) return 0;  // dangling link or a cycle
    visiting.insert(id);
    int d = 0;
    for (const auto& [port, source] : node->second.inputs) d = std::max(d, visit(source.node) + 1);
    visiting.erase(id);
    depth[id] = d;
    return d;
  };
  std::map<int, int> rows;
  std::map<std::string, int> row_of;
  for (const auto& [id, node] : graph.nodes) row_of[id] = rows[visit(id)]++;
  // A long pipeline (the flagship graph is fourteen columns deep) wraps into bands of
  // kBandColumns columns, one under the other, so a fitted view stays readable.
  constexpr int kBandColumns = 6;
  std::map<int, int> band_rows;  // rows used by each band
  for (const auto& [column, count] : rows) {
    int& used = band_rows[column / kBandColumns];
    used = std::max(used, count);
  }
  std::map<int, float> band_top;
  float top = 0;
  for (const auto& [band, used] : band_rows) {
    band_top[band] = top;
    top += used * kRowStep + kRowStep * 0.5f;
  }
  std::map<std::string, Position> out;
  for (const auto& [id, row] : row_of) {
    int column = depth[id];
    out[id] = Position{(column % kBandColumns) * kColumnStep,
                       band_top[column / kBandColumns] + row * kRowStep};
  }
  return out;
}

std::vector<std::string> place_unplaced_nodes(Graph& graph, const Registry* registry) {
  std::map<std::string, Position> automatic;
  std::vector<std::string> placed;
  for (const auto& [id, node] : graph.nodes) {
    if (read_position(graph, id)) continue;
    if (automatic.empty()) automatic = automatic_positions(graph, registry);
    write_position(graph, id, automatic[id]);
    placed.push_back(id);
  }
  return placed;
}

nlohmann::json shortest_number(const nlohmann::json& value) {
  if (!value.is_number_float()) return value;
  const double wide = value.get<double>();
  const float narrow = static_cast<float>(wide);
  if (!std::isfinite(wide) || static_cast<double>(narrow) != wide) return value;
  // The value came from a float (an ImGui slider): its shortest float text, read as a double,
  // is what the user typed or saw ("0.3", not 0.30000001192092896).
  char text[64];
  auto [end, error] = std::to_chars(text, text + sizeof text, narrow);
  if (error != std::errc{}) return value;
  double shortest = 0;
  std::from_chars(text, end, shortest);
  return shortest;
}

// ---- Document ------------------------------------------------------------------------------

Document::Document(const Registry& registry) : registry_(registry) {}

bool Document::dirty() const {
  uint64_t top = undo_.empty() ? 0 : undo_.back().serial;
  return saved_unknown_ || top != saved_serial_;
}

void Document::reset_history() {
  undo_.clear();
  redo_.clear();
  gesture_open_ = false;
  saved_serial_ = 0;
  saved_unknown_ = false;
  autosaved_revision_ = 0;
  touch();
}

void Document::new_graph(const std::string& path) {
  graph_ = Graph{};
  file_text_.clear();
  auto_placed_.clear();
  graph_.source_path = path;
  path_ = path;
  reset_history();
}

Status Document::open(const std::string& path) {
  // Only a regular file of a graph's size: a FIFO would block the window for ever.
  std::string text, why;
  if (!files::read_regular_file(path, kMaxEditorFileBytes, &text, &why)) {
    return make_error("cannot open " + quote_for_message(path) + ": " + why);
  }
  // Refuse only text that is not JSON at all; a graph that reads but fails validation opens so
  // the user can fix it here.
  if (!nlohmann::json::accept(text)) {
    ReadResult read = read_graph_text(text, registry_, path);
    return make_error_lines("cannot read '" + path + "': " + format_problems(read.problems));
  }
  ReadResult read = read_graph_text(text, registry_, path);
  graph_ = std::move(read.graph);
  graph_.source_path = path;
  file_text_ = text;
  // A graph written by hand has no positions: place them once, so the canvas does not
  // rearrange itself while links are edited. Not an edit: the file is not marked changed,
  // and saving it unedited leaves them out.
  auto_placed_ = place_unplaced_nodes(graph_, &registry_);
  path_ = path;
  std::error_code ignored;
  disk_time_ = fs::last_write_time(path, ignored);
  overwrite_confirmed_ = false;
  reset_history();
  return Ok{};
}

Status Document::save() {
  if (path_.empty()) return make_error("the graph has no file yet: use Save As and name one");
  std::error_code error;
  auto on_disk = fs::last_write_time(path_, error);
  if (!error && on_disk != disk_time_ && !overwrite_confirmed_) {
    overwrite_confirmed_ = true;
    return make_error("'" + path_ +
                      "' was changed on disk since it was opened: Save again to "
                      "overwrite it, or Save As to keep both");
  }
  return save_as(path_, /*replace=*/true);
}

bool Document::would_replace(const std::string& path) const {
  std::error_code error;
  if (!fs::exists(path, error)) return false;
  if (path_.empty()) return true;
  return !fs::equivalent(path, path_, error);
}

std::string Document::text_to_save() const {
  Graph to_save = graph_;
  // Positions placed automatically at open are not the user's until the graph is edited.
  if (!can_undo() && !saved_unknown_) {
    for (const auto& id : auto_placed_) write_position(to_save, id, std::nullopt);
    if (to_save.editor.is_object() && to_save.editor.contains("positions") &&
        to_save.editor["positions"].empty()) {
      to_save.editor.erase("positions");
    }
  }
  return write_graph_text(to_save, file_text_);
}

Status Document::save_as(const std::string& path, bool replace) {
  if (!replace && would_replace(path)) {
    return make_error("'" + path +
                      "' exists already: confirm to replace it, or choose another name");
  }
  // Saving onto the graph's own file is what Save is for; onto an image or mesh it reads is not.
  std::vector<ReadFile> reads = files_read_by(graph_, registry_);
  std::erase_if(reads, [](const ReadFile& read) { return read.role == "the graph file"; });
  if (auto may = check_may_write("Save As", path, reads); !may.ok()) return may;
  const std::string text = text_to_save();
  Status saved = save_graph_text(text, path);
  if (!saved) return saved;
  file_text_ = text;
  std::string old_autosave = autosave_path();
  path_ = path;
  graph_.source_path = path;
  std::error_code time_error;
  disk_time_ = fs::last_write_time(path, time_error);
  overwrite_confirmed_ = false;
  saved_serial_ = undo_.empty() ? 0 : undo_.back().serial;
  saved_unknown_ = false;
  gesture_open_ = false;  // an edit after saving must not merge into the saved state
  std::error_code ignored;
  fs::remove(old_autosave, ignored);
  fs::remove(autosave_path(), ignored);
  autosaved_revision_ = revision_;
  return Ok{};
}

std::string Document::autosave_path() const {
  if (path_.empty()) {
    return (fs::temp_directory_path() / "aquarelle-untitled.autosave.json").string();
  }
  fs::path path(path_);
  if (path.extension() == ".json") path.replace_extension("");
  return path.string() + ".autosave.json";
}

Result<bool> Document::autosave() {
  if (!dirty() || autosaved_revision_ == revision_) return false;
  Status written = save_graph_text(text_to_save(), autosave_path());
  if (!written) return make_error("autosave failed: " + written.message());
  autosaved_revision_ = revision_;
  return true;
}

bool Document::has_recovery() const {
  std::error_code error;
  fs::path side = autosave_path();
  if (!fs::exists(side, error)) return false;
  if (path_.empty() || !fs::exists(path_, error)) return true;
  return fs::last_write_time(side, error) >= fs::last_write_time(path_, error);
}

Status Document::recover() {
  std::string side = autosave_path();
  std::string text, why;
  if (!files::read_regular_file(side, kMaxEditorFileBytes, &text, &why)) {
    return make_error("cannot recover the autosave " + quote_for_message(side) + ": " + why);
  }
  if (!nlohmann::json::accept(text)) {
    return make_error("the autosave '" + side + "' is not valid JSON; delete it");
  }
  ReadResult read = read_graph_text(text, registry_, side);
  place_unplaced_nodes(read.graph, &registry_);
  Change change;
  change.label = "recover autosave";
  std::set<std::string> ids;
  for (const auto& [id, node] : graph_.nodes) ids.insert(id);
  for (const auto& [id, node] : read.graph.nodes) ids.insert(id);
  for (const auto& id : ids) {
    change.before[id] = state_of(id);
    NodeState after;
    auto it = read.graph.nodes.find(id);
    if (it != read.graph.nodes.end()) after.node = it->second;
    after.position = read_position(read.graph, id);
    change.after[id] = after;
  }
  change.output_before = graph_.output;
  change.output_after = read.graph.output;
  change.settings_before = graph_.settings;
  change.settings_after = read.graph.settings;
  commit(std::move(change));
  saved_unknown_ = true;  // what is on screen now is in no saved file
  return Ok{};
}

void Document::discard_recovery() {
  std::error_code ignored;
  fs::remove(autosave_path(), ignored);
}

const std::vector<Problem>& Document::problems() const {
  if (problems_revision_ != revision_) {
    problems_ = validate_graph(graph_, registry_);
    problems_revision_ = revision_;
  }
  return problems_;
}

std::vector<Problem> Document::problems_of(const std::string& node_id) const {
  std::vector<Problem> out;
  for (const auto& problem : problems()) {
    if (problem.node == node_id) out.push_back(problem);
  }
  return out;
}

std::optional<Position> Document::position(const std::string& node_id) const {
  return read_position(graph_, node_id);
}

NodeState Document::state_of(const std::string& id) const {
  NodeState state;
  auto it = graph_.nodes.find(id);
  if (it != graph_.nodes.end()) state.node = it->second;
  state.position = read_position(graph_, id);
  state.bypassed = read_bypassed(graph_, id);
  return state;
}

void Document::apply_side(const std::map<std::string, NodeState>& side,
                          const std::optional<PortRef>& output, const Settings& settings) {
  for (const auto& [id, state] : side) {
    if (state.node) {
      graph_.nodes[id] = *state.node;
    } else {
      graph_.nodes.erase(id);
    }
    write_position(graph_, id, state.position);
    write_bypassed(graph_, id, state.bypassed);
  }
  graph_.output = output;
  graph_.settings = settings;
  touch();
}

void Document::commit(Change change) {
  redo_.clear();
  bool merge = gesture_open_ && !change.coalesce_key.empty() && !undo_.empty() &&
               undo_.back().coalesce_key == change.coalesce_key;
  apply_side(change.after, change.output_after, change.settings_after);
  if (change.extras_after) apply_extras(*change.extras_after);
  if (merge) {
    Change& last = undo_.back();
    if (change.extras_after) {
      if (!last.extras_before) last.extras_before = change.extras_before;
      last.extras_after = change.extras_after;
    }
    // The merged step undoes to the state before the gesture began.
    for (auto& [id, state] : change.before) last.before.try_emplace(id, state);
    for (auto& [id, state] : change.after) last.after[id] = state;
    last.output_after = change.output_after;
    last.settings_after = change.settings_after;
    last.label = change.label;
    last.serial = next_serial_++;
  } else {
    change.serial = next_serial_++;
    undo_.push_back(std::move(change));
  }
  gesture_open_ = !undo_.back().coalesce_key.empty();
}

bool Document::undo() {
  if (undo_.empty()) return false;
  Change change = std::move(undo_.back());
  undo_.pop_back();
  apply_side(change.before, change.output_before, change.settings_before);
  if (change.extras_before) apply_extras(*change.extras_before);
  redo_.push_back(std::move(change));
  gesture_open_ = false;
  return true;
}

bool Document::redo() {
  if (redo_.empty()) return false;
  Change change = std::move(redo_.back());
  redo_.pop_back();
  apply_side(change.after, change.output_after, change.settings_after);
  if (change.extras_after) apply_extras(*change.extras_after);
  undo_.push_back(std::move(change));
  gesture_open_ = false;
  return true;
}

std::string Document::free_id(const std::string& type) const {
  std::string base = type.empty() ? "node" : type;
  if (!graph_.nodes.count(base)) return base;
  for (int n = 2;; ++n) {
    std::string id = base + std::to_string(n);
    if (!graph_.nodes.count(id)) return id;
  }
}

// ---- Edits ---------------------------------------------------------------------------------

Result<std::string> Document::add_node(const std::string& type, Position at,
                                       const std::string& wanted_id) {
  const NodeType* node_type = registry_.find(type);
  if (node_type == nullptr) {
    return make_error("cannot add a node of type '" + type + "': no installed plugin provides it" +
                      " (installed: " + join(registry_.names()) + ")");
  }
  std::string id = wanted_id.empty() ? free_id(type) : wanted_id;
  if (graph_.nodes.count(id)) return make_error("cannot add node '" + id + "': the id is taken");
  if (id.empty() || id.find('.') != std::string::npos) {
    return make_error("cannot add node '" + id + "': an id must be non-empty and have no '.'");
  }
  Change change;
  change.label = "add " + id;
  change.before[id] = state_of(id);
  Node node;
  node.type = type;
  change.after[id] = NodeState{node, at};
  change.output_before = change.output_after = graph_.output;
  change.settings_before = change.settings_after = graph_.settings;
  // A graph without an output shows the first node added.
  if (!graph_.output && !node_type->outputs.empty()) {
    change.output_after = PortRef{id, node_type->outputs.front().name};
  }
  commit(std::move(change));
  return id;
}

std::optional<PortRef> Document::source_around(PortRef read,
                                               const std::set<std::string>& doomed) const {
  for (size_t step = 0; step <= doomed.size(); ++step) {
    auto node = graph_.nodes.find(read.node);
    if (node == graph_.nodes.end()) return std::nullopt;
    const NodeType* type = registry_.find(node->second.type);
    if (type == nullptr || type->inputs.empty()) return std::nullopt;
    auto out = std::find_if(type->outputs.begin(), type->outputs.end(),
                            [&](const PortInfo& port) { return port.name == read.port; });
    const PortInfo& first = type->inputs.front();
    auto link = node->second.inputs.find(first.name);
    if (out == type->outputs.end() || first.type != out->type ||
        link == node->second.inputs.end()) {
      return std::nullopt;
    }
    if (!doomed.count(link->second.node)) return link->second;
    read = link->second;  // a chain of deleted nodes: around all of them
  }
  return std::nullopt;
}

Status Document::remove_nodes(const std::vector<std::string>& ids, bool reconnect) {
  std::set<std::string> doomed;
  for (const auto& id : ids) {
    if (!graph_.nodes.count(id)) return make_error("cannot delete node '" + id + "': no such node");
    doomed.insert(id);
  }
  if (doomed.empty()) return make_error("nothing to delete: select nodes first");
  Change change;
  change.label = doomed.size() == 1 ? "delete " + *doomed.begin()
                                    : "delete " + std::to_string(doomed.size()) + " nodes";
  for (const auto& id : doomed) {
    change.before[id] = state_of(id);
    change.after[id] = NodeState{};
  }
  for (const auto& [id, node] : graph_.nodes) {
    if (doomed.count(id)) continue;
    Node kept = node;
    bool changed = false;
    for (auto it = kept.inputs.begin(); it != kept.inputs.end();) {
      if (!doomed.count(it->second.node)) {
        ++it;
        continue;
      }
      changed = true;
      const auto around = reconnect ? source_around(it->second, doomed) : std::nullopt;
      if (around) {
        it->second = *around;
        ++it;
      } else {
        it = kept.inputs.erase(it);
      }
    }
    if (changed) {
      change.before[id] = state_of(id);
      change.after[id] = NodeState{kept, read_position(graph_, id)};
    }
  }
  // Groups forget deleted members; a group left empty goes.
  auto groups = read_groups(graph_);
  bool regrouped = false;
  for (auto& group : groups) {
    regrouped |= std::erase_if(group.nodes, [&](const auto& id) { return doomed.count(id); }) > 0;
  }
  if (regrouped) {
    std::erase_if(groups, [](const Group& group) { return group.nodes.empty(); });
    Graph edited = graph_;
    write_groups(edited, groups);
    change.extras_before =
        nlohmann::json{{"groups", graph_.editor.value("groups", nlohmann::json())}};
    change.extras_after =
        nlohmann::json{{"groups", edited.editor.value("groups", nlohmann::json())}};
  }
  change.output_before = change.output_after = graph_.output;
  if (graph_.output && doomed.count(graph_.output->node)) {
    change.output_after =
        reconnect ? source_around(*graph_.output, doomed) : std::optional<PortRef>();
  }
  change.settings_before = change.settings_after = graph_.settings;
  commit(std::move(change));
  return Ok{};
}

Result<std::vector<std::string>> Document::duplicate_nodes(const std::vector<std::string>& ids,
                                                           Position offset) {
  if (ids.empty()) return make_error("nothing to duplicate: select nodes first");
  std::map<std::string, std::string> new_id_of;
  Change change;
  Graph scratch = graph_;  // to hand out ids that do not collide with each other
  for (const auto& id : ids) {
    auto it = graph_.nodes.find(id);
    if (it == graph_.nodes.end()) {
      return make_error("cannot duplicate node '" + id + "': no such node");
    }
    if (new_id_of.count(id)) continue;
    std::string fresh;
    for (int n = 2;; ++n) {
      // Copies of "blur" are "blur2", "blur3"...; copies of "blur2" are "blur3"... as well.
      std::string base = it->second.type;
      fresh = n == 2 && !scratch.nodes.count(base) ? base : base + std::to_string(n);
      if (!scratch.nodes.count(fresh)) break;
    }
    scratch.nodes[fresh] = it->second;
    new_id_of[id] = fresh;
  }
  std::vector<std::string> created;
  for (const auto& id : ids) {
    const std::string& fresh = new_id_of[id];
    if (change.after.count(fresh)) continue;
    Node copy = graph_.nodes.at(id);
    for (auto& [port, source] : copy.inputs) {
      auto inner = new_id_of.find(source.node);
      if (inner != new_id_of.end()) source.node = inner->second;
    }
    Position at = read_position(graph_, id).value_or(Position{});
    change.before[fresh] = NodeState{};
    change.after[fresh] = NodeState{copy, Position{at.x + offset.x, at.y + offset.y}};
    created.push_back(fresh);
  }
  change.label = created.size() == 1 ? "duplicate " + ids.front()
                                     : "duplicate " + std::to_string(created.size()) + " nodes";
  change.output_before = change.output_after = graph_.output;
  change.settings_before = change.settings_after = graph_.settings;
  commit(std::move(change));
  return created;
}

bool Document::depends_on(const std::string& node, const std::string& upstream) const {
  std::vector<std::string> stack{node};
  std::set<std::string> seen;
  while (!stack.empty()) {
    std::string current = stack.back();
    stack.pop_back();
    if (current == upstream) return true;
    if (!seen.insert(current).second) continue;
    auto it = graph_.nodes.find(current);
    if (it == graph_.nodes.end()) continue;
    for (const auto& [port, source] : it->second.inputs) stack.push_back(source.node);
  }
  return false;
}

std::string Document::why_not_link(const PortRef& from, const std::string& to_node,
                                   const std::string& to_input) const {
  const std::string what = "cannot link " + from.str() + " to " + to_node + "." + to_input + ": ";
  auto source = graph_.nodes.find(from.node);
  if (source == graph_.nodes.end()) return what + "there is no node '" + from.node + "'";
  auto target = graph_.nodes.find(to_node);
  if (target == graph_.nodes.end()) return what + "there is no node '" + to_node + "'";
  const NodeType* source_type = registry_.find(source->second.type);
  if (source_type == nullptr) {
    return what + "node '" + from.node + "' has type '" + source->second.type +
           "', which no installed plugin provides";
  }
  const NodeType* target_type = registry_.find(target->second.type);
  if (target_type == nullptr) {
    return what + "node '" + to_node + "' has type '" + target->second.type +
           "', which no installed plugin provides";
  }
  const PortInfo* output = source_type->output(from.port);
  if (output == nullptr) {
    std::vector<std::string> names;
    for (const auto& port : source_type->outputs) names.push_back(port.name);
    return what + "'" + source_type->name + "' has no output '" + from.port +
           "' (outputs: " + join(names) + ")";
  }
  const PortInfo* input = target_type->input(to_input);
  if (input == nullptr) {
    std::vector<std::string> names;
    for (const auto& port : target_type->inputs) names.push_back(port.name);
    return what + "'" + target_type->name + "' has no input '" + to_input +
           "' (inputs: " + join(names) + ")";
  }
  if (output->type != input->type) {
    return what + "incompatible port types: the output gives " + port_type_name(output->type) +
           ", the input takes " + port_type_name(input->type);
  }
  if (from.node == to_node) return what + "a node cannot read its own output";
  if (depends_on(from.node, to_node)) {
    return what + "it would close a cycle ('" + from.node + "' already depends on '" + to_node +
           "')";
  }
  return "";
}

Status Document::link(const PortRef& from, const std::string& to_node,
                      const std::string& to_input) {
  std::string why = why_not_link(from, to_node, to_input);
  if (!why.empty()) return make_error(why);
  Change change;
  change.label = "link " + from.str() + " -> " + to_node + "." + to_input;
  change.before[to_node] = state_of(to_node);
  NodeState after = state_of(to_node);
  // A port that takes many links (scene_join's `objects`) gains one; others replace theirs.
  const NodeType* target_type = registry_.find(after.node->type);
  const PortInfo* port = target_type != nullptr ? target_type->input(to_input) : nullptr;
  const std::vector<PortRef> existing = after.node->inputs.links(to_input);
  if (port != nullptr && port->multi) {
    if (std::find(existing.begin(), existing.end(), from) == existing.end()) {
      after.node->inputs.add(to_input, from);
    }
  } else {
    after.node->inputs[to_input] = from;
  }
  change.after[to_node] = after;
  change.output_before = change.output_after = graph_.output;
  change.settings_before = change.settings_after = graph_.settings;
  commit(std::move(change));
  return Ok{};
}

Status Document::unlink(const std::string& node, const std::string& input) {
  auto it = graph_.nodes.find(node);
  if (it == graph_.nodes.end()) return make_error("cannot unlink: there is no node '" + node + "'");
  if (!it->second.inputs.count(input)) {
    return make_error("cannot unlink " + node + "." + input + ": that input is not linked");
  }
  Change change;
  change.label = "unlink " + node + "." + input;
  change.before[node] = state_of(node);
  NodeState after = state_of(node);
  after.node->inputs.erase(input);
  change.after[node] = after;
  change.output_before = change.output_after = graph_.output;
  change.settings_before = change.settings_after = graph_.settings;
  commit(std::move(change));
  return Ok{};
}

Status Document::move_nodes(const std::map<std::string, Position>& positions,
                            const std::string& coalesce_key) {
  if (positions.empty()) return Ok{};
  if (std::any_of(positions.begin(), positions.end(),
                  [](const auto& entry) { return group_name_of_item(entry.first).has_value(); })) {
    return move_with_groups(positions, coalesce_key);
  }
  Change change;
  for (const auto& [id, at] : positions) {
    if (!graph_.nodes.count(id)) return make_error("cannot move node '" + id + "': no such node");
    change.before[id] = state_of(id);
    NodeState after = state_of(id);
    after.position = at;
    change.after[id] = after;
  }
  change.label = positions.size() == 1 ? "move " + positions.begin()->first
                                       : "move " + std::to_string(positions.size()) + " nodes";
  change.output_before = change.output_after = graph_.output;
  change.settings_before = change.settings_after = graph_.settings;
  change.coalesce_key = coalesce_key;
  commit(std::move(change));
  return Ok{};
}

Status Document::set_param(const std::string& node, const std::string& param,
                           const nlohmann::json& value, const std::string& coalesce_key) {
  auto it = graph_.nodes.find(node);
  if (it == graph_.nodes.end()) {
    return make_error("cannot set " + node + "." + param + ": there is no node '" + node + "'");
  }
  const NodeType* type = registry_.find(it->second.type);
  if (type == nullptr) {
    return make_error("cannot set " + node + "." + param + ": node type '" + it->second.type +
                      "' is not installed");
  }
  const ParamInfo* info = type->param(param);
  if (info == nullptr) {
    std::vector<std::string> names;
    for (const auto& p : type->params) names.push_back(p.name);
    return make_error("cannot set " + node + "." + param + ": '" + type->name +
                      "' has no parameter '" + param + "' (parameters: " + join(names) + ")");
  }
  nlohmann::json stored = value;
  if (!value.is_null()) {
    std::string why = why_bad_param_value(*info, value);
    if (!why.empty()) return make_error("cannot set node '" + node + "', " + why);
    // Ints arrive from sliders and scripts as 3.0 as often as 3; store them whole.
    if (info->type == AQ_PARAM_INT)
      stored = static_cast<int64_t>(std::llround(value.get<double>()));
    if (info->type == AQ_PARAM_FLOAT) stored = shortest_number(value);
    if ((info->type == AQ_PARAM_VEC3 || info->type == AQ_PARAM_COLOR) && value.is_array()) {
      for (auto& component : stored) component = shortest_number(component);
    }
  }
  NodeState after = state_of(node);
  if (stored.is_null()) {
    after.node->params.erase(param);
  } else {
    after.node->params[param] = stored;
  }
  if (after.node->params == it->second.params) return Ok{};  // no change, no undo step
  Change change;
  change.label = "set " + node + "." + param;
  change.before[node] = state_of(node);
  change.after[node] = after;
  change.output_before = change.output_after = graph_.output;
  change.settings_before = change.settings_after = graph_.settings;
  change.coalesce_key = coalesce_key;
  commit(std::move(change));
  return Ok{};
}

Status Document::set_output(const std::optional<PortRef>& output) {
  if (output) {
    auto it = graph_.nodes.find(output->node);
    if (it == graph_.nodes.end()) {
      return make_error("cannot show " + output->str() + ": there is no node '" + output->node +
                        "'");
    }
    const NodeType* type = registry_.find(it->second.type);
    if (type != nullptr && type->output(output->port) == nullptr) {
      return make_error("cannot show " + output->str() + ": '" + type->name + "' has no output '" +
                        output->port + "'");
    }
  }
  if (output == graph_.output) return Ok{};
  Change change;
  change.label = output ? "set output " + output->str() : "clear output";
  change.output_before = graph_.output;
  change.output_after = output;
  change.settings_before = change.settings_after = graph_.settings;
  commit(std::move(change));
  return Ok{};
}

Status Document::set_settings(const Settings& settings) {
  if (settings.width < 1 || settings.height < 1) {
    return make_error("the resolution must be at least 1x1");
  }
  if (!(settings.fps > 0)) return make_error("fps must be positive");
  if (settings.last_frame < settings.first_frame) {
    return make_error("the last frame must not come before the first");
  }
  Change change;
  change.label = "change settings";
  change.output_before = change.output_after = graph_.output;
  change.settings_before = graph_.settings;
  change.settings_after = settings;
  commit(std::move(change));
  return Ok{};
}

}  // namespace aq::editor
