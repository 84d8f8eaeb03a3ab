// The editor's document: the one aq::Graph being edited, every edit as an undoable command,
// the file it belongs to (save, save as, dirty flag) and its autosave side file.
//
// The editor never keeps a second copy of the graph: the canvas, the parameter panel and the
// viewer read document.graph() and change it only through the edit functions below, which
// check the edit against the registry first and refuse it with a reason (a link between
// incompatible ports, a link that closes a cycle, an unknown port or parameter...).
//
//   edit function ──► checks ──► Change {before, after of each touched node} ──► undo stack
//                        └─ refused: Status with the reason, graph untouched
//
// A Change records, for every node it touches, the node and its editor position before and
// after, plus the graph's output and settings; undo writes back the "before" side, redo the
// "after" side. Continuous edits (a slider drag, a node drag) pass a coalesce key so one
// gesture is one undo step; end_gesture() closes it.
#pragma once

#include <aquarelle/core/graph.h>
#include <aquarelle/core/graph_io.h>
#include <aquarelle/core/registry.h>
#include <aquarelle/core/result.h>

#include <nlohmann/json.hpp>

#include <cstdint>
#include <filesystem>
#include <map>
#include <optional>
#include <set>
#include <string>
#include <utility>
#include <vector>

namespace aq::editor {

// The largest graph, autosave or script the editor reads (as `render` reads graphs).
inline constexpr uint64_t kMaxEditorFileBytes = 64ull << 20;

struct Position {
  float x = 0;
  float y = 0;
  bool operator==(const Position&) const = default;
};

// One node's state as far as an edit is concerned: the node itself (absent = no such node)
// and its position on the canvas (absent = not placed yet).
struct NodeState {
  std::optional<Node> node;
  std::optional<Position> position;
  bool bypassed = false;  // the node's bypass (kept with the node; here for clarity of edits)
};

// What one edit changed; applying `after` redoes it, applying `before` undoes it.
struct Change {
  std::string label;  // "link blur.image → vignette.image", shown in the Edit menu
  std::map<std::string, NodeState> before;
  std::map<std::string, NodeState> after;
  std::optional<PortRef> output_before;
  std::optional<PortRef> output_after;
  Settings settings_before;
  Settings settings_after;
  // editor.backdrops and editor.reroutes before and after, when the change touches them.
  std::optional<nlohmann::json> extras_before;
  std::optional<nlohmann::json> extras_after;
  std::string coalesce_key;  // non-empty: later edits with the same key merge into this one
  uint64_t serial = 0;       // unique per change, for the dirty flag
};

class Document {
 public:
  explicit Document(const Registry& registry);

  // ---- Files --------------------------------------------------------------------------
  // Reads and validates GRAPH. A file whose JSON cannot be read is refused; a graph with
  // validation problems (an unknown node type, a missing input...) opens so it can be fixed,
  // and its problems are listed by problems().
  Status open(const std::string& path);
  // An empty graph; `path` (optional) is the file Save will write, e.g. a file that does not
  // exist yet.
  void new_graph(const std::string& path = "");
  // Canonical, atomic writes through aq::save_graph_file; clears the dirty flag and removes
  // the autosave side file.
  // Saving patches the text the graph was read from (aq::write_graph_text with the original):
  // an unedited graph saves to the same bytes, an edit changes only the lines it concerns.
  Status save();
  // Refuses to replace an existing file other than the graph's own unless `replace` (the user
  // confirmed): would_replace() says when the editor must ask first.
  Status save_as(const std::string& path, bool replace = false);
  bool would_replace(const std::string& path) const;
  // The text save() would write now.
  std::string text_to_save() const;
  const std::string& path() const { return path_; }
  bool dirty() const;

  // ---- Autosave and recovery -----------------------------------------------------------
  // GRAPH.json → GRAPH.autosave.json next to it; an untitled graph autosaves in the temp dir.
  std::string autosave_path() const;
  // Writes the side file when there are changes it does not hold yet; returns whether written.
  Result<bool> autosave();
  // True when a side file exists that is newer than the graph file (a crash left it).
  bool has_recovery() const;
  // Replaces the graph with the side file's (as an undoable change, marked unsaved).
  Status recover();
  void discard_recovery();

  // ---- The model -----------------------------------------------------------------------
  const Graph& graph() const { return graph_; }
  const Registry& registry() const { return registry_; }
  // Changes every time the graph changes (edits, undo, redo, open): views compare it to know
  // when to re-validate and re-evaluate.
  uint64_t revision() const { return revision_; }
  // Validation problems of the current graph (cached per revision).
  const std::vector<Problem>& problems() const;
  std::vector<Problem> problems_of(const std::string& node_id) const;
  std::optional<Position> position(const std::string& node_id) const;

  // ---- Edits: each is one undoable command, or refused with a reason --------------------
  // Adds a node of `type`; the id is `type` or `type2`, `type3`... (or `wanted_id` when free).
  Result<std::string> add_node(const std::string& type, Position at,
                               const std::string& wanted_id = "");
  // Removes the nodes and every link into them; the output is cleared if it named one.
  // `reconnect` (Del in the canvas, as Nuke and Blender do): a reader of a deleted node is
  // linked to what fed the deleted node's first input, when that carries the port type it read
  // (the graph's output too); one undo step.
  Status remove_nodes(const std::vector<std::string>& ids, bool reconnect = false);
  // Copies the nodes with new ids, their parameters, the links among them and the links into
  // them from outside; the copies sit at `offset` from the originals. Returns the new ids.
  Result<std::vector<std::string>> duplicate_nodes(const std::vector<std::string>& ids,
                                                   Position offset = {40, 40});
  // Links an output to an input (replacing the input's previous link; a port that takes many
  // links gains one unless it has it already). Refused: unknown node,
  // port or type, incompatible port types, a link from a node to itself or one closing a cycle.
  Status link(const PortRef& from, const std::string& to_node, const std::string& to_input);
  // The reason link() would refuse, or an empty string when it would accept.
  std::string why_not_link(const PortRef& from, const std::string& to_node,
                           const std::string& to_input) const;
  Status unlink(const std::string& node, const std::string& input);
  // Moves nodes (or collapsed groups, by group_item_id) to absolute positions. Pass a coalesce
  // key (e.g. "move") for a drag.
  Status move_nodes(const std::map<std::string, Position>& positions,
                    const std::string& coalesce_key = "");
  // Sets a parameter (checked against its type and range); a null value resets it to its
  // default. Pass a coalesce key (e.g. "param:blur.sigma") for a slider drag.
  Status set_param(const std::string& node, const std::string& param, const nlohmann::json& value,
                   const std::string& coalesce_key = "");
  Status set_output(const std::optional<PortRef>& output);
  Status set_settings(const Settings& settings);
  // Ends a continuous gesture: the next edit starts a new undo step even with the same key.
  void end_gesture() { gesture_open_ = false; }
  // A continuous gesture (slider or node drag) is under way.
  bool in_gesture() const { return gesture_open_; }

  // ---- Undo and redo -------------------------------------------------------------------
  bool can_undo() const { return !undo_.empty(); }
  bool can_redo() const { return !redo_.empty(); }
  std::string undo_label() const { return undo_.empty() ? "" : undo_.back().label; }
  std::string redo_label() const { return redo_.empty() ? "" : redo_.back().label; }
  bool undo();
  bool redo();

  // A free node id for `type` ("blur", then "blur2", "blur3"...).
  std::string free_id(const std::string& type) const;

  // ---- Nuke-style editing: each one undo step ---------------------------------------------
  // The nodes as graph JSON text (the system clipboard's content): their definitions, the
  // links among them and into them, their positions.
  std::string copy_nodes(const std::vector<std::string>& ids) const;
  // Adds the nodes of a copied text: fresh ids where taken (links among them follow), links to
  // nodes this graph lacks dropped; their top-left lands at `at` when given, else 40 units
  // right of and below where they were. Returns the new ids.
  Result<std::vector<std::string>> paste_nodes(const std::string& text,
                                               std::optional<Position> at = std::nullopt);
  // A new node at `at` wired after `after`: its first input of that output's type reads it, and
  // everything that read `after` (links, the graph output) now reads the new node.
  Result<std::string> insert_node_after(const std::string& type, Position at, const PortRef& after);
  // A new node dropped on the link into `to_node.to_input`: source → new → to_node.
  Result<std::string> insert_node_on_link(const std::string& type, Position at,
                                          const std::string& to_node, const std::string& to_input);
  // An unlinked node dropped onto the link into `to_node.to_input`: source → id → to_node.
  Status splice_into_link(const std::string& id, const std::string& to_node,
                          const std::string& to_input);
  // Renames a node; links, the output, its position and bypass follow.
  Status rename_node(const std::string& id, const std::string& new_id);
  // Bypassed nodes pass their first input of each output's type through (core/bypass.h).
  Status set_bypassed(const std::vector<std::string>& ids, bool bypassed);
  bool bypassed(const std::string& id) const;
  // Moves every node to the automatic layout (columns by depth).
  Status auto_layout();

  // ---- Backdrops: labelled frames behind groups of nodes (editor.backdrops) ---------------
  // A backdrop around the nodes (with a margin and a title bar); returns its index.
  Result<size_t> add_backdrop(const std::vector<std::string>& around, const std::string& label);
  Status set_backdrop_label(size_t index, const std::string& label);
  Status remove_backdrop(size_t index);
  // Moves the backdrop and the nodes inside it by (dx, dy). Pass a coalesce key for a drag.
  Status move_backdrop(size_t index, Position by, const std::string& coalesce_key = "");

  // ---- Reroute dots: points a link is drawn through (editor.reroutes) ---------------------
  Status add_reroute(const std::string& node, const std::string& input, Position at);
  Status move_reroute(const std::string& node, const std::string& input, size_t index, Position to,
                      const std::string& coalesce_key = "");
  Status remove_reroute(const std::string& node, const std::string& input, size_t index);

  // ---- Node groups: a sub-graph shown as one node (editor.groups) -------------------------
  // Groups the nodes (none may be in a group already) collapsed, at their top-left; returns the
  // group's name ("Group", "Group2"... unless `name` is given and free).
  Result<std::string> group_nodes(const std::vector<std::string>& ids,
                                  const std::string& name = "");
  // Collapses (true) or expands (false) a group.
  Status set_group_collapsed(const std::string& name, bool collapsed);
  // Removes the group; its nodes stay where they are, shown again.
  Status ungroup(const std::string& name);
  Status rename_group(const std::string& name, const std::string& new_name);

 private:
  // What feeds a reader of `read` once the nodes in `doomed` are gone (see remove_nodes).
  std::optional<PortRef> source_around(PortRef read, const std::set<std::string>& doomed) const;
  NodeState state_of(const std::string& id) const;
  void apply_side(const std::map<std::string, NodeState>& side, const std::optional<PortRef>& out,
                  const Settings& settings);
  // Records and applies a change (merging into the last one when the gesture continues).
  void commit(Change change);
  void reset_history();
  void touch() { ++revision_; }
  bool depends_on(const std::string& node, const std::string& upstream) const;
  // A new node wired after `after`; every reader of it moves to the new node, or only the
  // link into only_link (node, input).
  Result<std::string> insert_node(
      const std::string& type, Position at, const PortRef& after,
      const std::optional<std::pair<std::string, std::string>>& only_link);
  // Records the difference between the graph and `edited` (nodes, positions, bypass, output,
  // settings) as one change.
  void commit_edit(const std::string& label, const Graph& edited,
                   const std::string& coalesce_key = "");
  // move_nodes when some of the items moved are collapsed groups (their nodes move with them).
  Status move_with_groups(const std::map<std::string, Position>& positions,
                          const std::string& coalesce_key);
  // editor[key] = value for each key of `value` (null: removed).
  void apply_extras(const nlohmann::json& value);
  // The first input of `type_node` that accepts an output of `type`, or "".
  std::string first_input_of_type(const std::string& node_type, aq_port_type type) const;

  const Registry& registry_;
  Graph graph_;
  std::string path_;
  std::string file_text_;                 // the text last read or written, patched on save
  std::vector<std::string> auto_placed_;  // nodes placed at open, not by the user
  // The file's modification time when opened or last saved: save() refuses once to overwrite
  // a file someone else changed since, and a second save() is the user's confirmation.
  std::filesystem::file_time_type disk_time_{};
  bool overwrite_confirmed_ = false;
  std::vector<Change> undo_;
  std::vector<Change> redo_;
  bool gesture_open_ = false;
  uint64_t next_serial_ = 1;
  uint64_t saved_serial_ = 0;   // serial of the change on top of the stack when saved (0: none)
  bool saved_unknown_ = false;  // recovered from autosave: not equal to any saved state
  uint64_t revision_ = 1;
  uint64_t autosaved_revision_ = 0;
  mutable uint64_t problems_revision_ = 0;
  mutable std::vector<Problem> problems_;
};

// Positions live in graph.editor["positions"][id] = [x, y].
std::optional<Position> read_position(const Graph& graph, const std::string& id);
void write_position(Graph& graph, const std::string& id, const std::optional<Position>& position);

// Positions for nodes in columns by their longest path from a source (for graphs written by
// hand), and writing them for the nodes that have none.
// With `registry`, rows are spaced for the tallest node (a node with many ports, cel_light's
// eight inputs, is taller than the default row step).
std::map<std::string, Position> automatic_positions(const Graph& graph,
                                                    const Registry* registry = nullptr);
struct Backdrop {
  std::string label;
  Position at;  // top-left, canvas units
  float width = 0;
  float height = 0;
  bool contains(Position p) const {
    return p.x >= at.x && p.y >= at.y && p.x <= at.x + width && p.y <= at.y + height;
  }
};
// Backdrops live in graph.editor["backdrops"] = [{"label", "rect": [x, y, w, h]}...].
std::vector<Backdrop> read_backdrops(const Graph& graph);
void write_backdrops(Graph& graph, const std::vector<Backdrop>& backdrops);

// Reroute dots of the link into node.input, in graph.editor["reroutes"]["node.input"] =
// {"from": "<source>", "dots": [[x, y]...]}; dots made for a link since relinked are ignored.
std::vector<Position> read_reroutes(const Graph& graph, const std::string& node,
                                    const std::string& input);
void write_reroutes(Graph& graph, const std::string& node, const std::string& input,
                    const std::vector<Position>& dots);

// Bypass is the node's own ("bypass": true in the file, Node::bypass), so `aquarelle render`
// honours it too; the evaluator wires around bypassed nodes (aquarelle/core/bypass.h). Graphs
// that kept it in editor.bypassed are migrated when read.
bool read_bypassed(const Graph& graph, const std::string& id);
void write_bypassed(Graph& graph, const std::string& id, bool bypassed);

// A node group: presentation only (evaluation and `aquarelle render` never read it). Saved in
// graph.editor["groups"] = [{"name", "nodes": [ids], "collapsed", "position": [x, y]}...];
// `position` is where the collapsed group is drawn: moving it moves its nodes with it.
struct Group {
  std::string name;
  std::vector<std::string> nodes;
  bool collapsed = true;
  Position position;
};
std::vector<Group> read_groups(const Graph& graph);
void write_groups(Graph& graph, const std::vector<Group>& groups);
// The collapsed group that hides node `id`, if any.
const Group* collapsed_group_of(const std::vector<Group>& groups, const std::string& id);
// The top-left corner of the nodes' rectangles (where a group collapses to).
Position members_top_left(const Graph& graph, const Registry& registry,
                          const std::vector<std::string>& members);
// The id a collapsed group has on the canvas and in the selection: a node id never holds '.'.
std::string group_item_id(const std::string& name);
// The group's name when `item` is a group_item_id, else nullopt.
std::optional<std::string> group_name_of_item(const std::string& item);

// The ports a collapsed group shows: each is an inner node's port. Inputs: every input of a
// member linked from outside the group, and every required input left unlinked (so it can be
// linked); outputs: every member output read outside the group or giving the graph's output
// (when there is none: the outputs of the members no other member reads, the group's result).
struct GroupPort {
  PortRef inner;  // member node and its port
  aq_port_type type = AQ_PORT_IMAGE;
};
struct GroupPorts {
  std::vector<GroupPort> inputs;
  std::vector<GroupPort> outputs;
};
GroupPorts group_ports(const Graph& graph, const Registry& registry, const Group& group);
// The ids with every group item replaced by its member nodes (each id once, in order).
std::vector<std::string> expand_group_items(const Graph& graph,
                                            const std::vector<std::string>& ids);

// Returns the ids it placed.
std::vector<std::string> place_unplaced_nodes(Graph& graph, const Registry* registry = nullptr);

// A float parameter value that came from a float (an ImGui slider or field) as the shortest
// decimal that reads back to the same float: 0.30000001192092896 → 0.3. Other values as given.
nlohmann::json shortest_number(const nlohmann::json& value);

// The JSON shape a parameter value must have, or why `value` does not fit `param`.
std::string why_bad_param_value(const ParamInfo& param, const nlohmann::json& value);

}  // namespace aq::editor
