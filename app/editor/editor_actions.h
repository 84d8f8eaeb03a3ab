// Every editor action, as one function each: the canvas's mouse and keyboard handlers, the
// menus and the scripted mode all call these, so a script exercises the same code as a user.
// Each updates the status line (the refusal reason when the document refuses) and returns the
// document's answer.
#pragma once

#include "editor_state.h"

#include <aquarelle/core/result.h>

#include <map>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

namespace aq::editor::actions {

Result<std::string> add_node(EditorState& state, const std::string& type, Position at,
                             const std::string& wanted_id = "");
Status link(EditorState& state, const PortRef& from, const std::string& to_node,
            const std::string& to_input);
Status unlink(EditorState& state, const std::string& node, const std::string& input);
// `gesture`: part of a drag; call end_gesture() when the mouse is released.
Status move(EditorState& state, const std::map<std::string, Position>& positions,
            bool gesture = false);
Status set_param(EditorState& state, const std::string& node, const std::string& param,
                 const nlohmann::json& value, bool gesture = false);
void end_gesture(EditorState& state);

Status delete_nodes(EditorState& state, const std::vector<std::string>& ids);
Status delete_selection(EditorState& state);
Status duplicate_selection(EditorState& state);
void select(EditorState& state, const std::vector<std::string>& ids, bool add = false);
// Empties the selection (a click on empty canvas); the status line forgets the selection count.
void clear_selection(EditorState& state);

// Tab / the add menu: with one node selected, the new node is inserted after it (wired from its
// first output, its readers moved to the new node); otherwise it is added unlinked. Either way
// at `at` (the cursor), moved down until it overlaps no other node.
Result<std::string> add_node_at_cursor(EditorState& state, const std::string& type, Position at);
// Drops a new node onto the link into `to_node.to_input`.
Result<std::string> insert_on_link(EditorState& state, const std::string& type, Position at,
                                   const std::string& to_node, const std::string& to_input);
// The selection as graph JSON (for the system clipboard); "" when nothing is selected.
std::string copy_selection(EditorState& state);
// Pastes graph JSON; the pasted nodes become the selection, their top-left at `at` if given.
Status paste(EditorState& state, const std::string& text, std::optional<Position> at);
Status rename(EditorState& state, const std::string& id, const std::string& new_id);
// Bypasses the selection, or enables it again when every selected node is bypassed.
Status toggle_bypass(EditorState& state);
Status auto_layout(EditorState& state);
// Ctrl+G: the selected nodes become a collapsed group (selected); the selected nodes of an
// expanded group collapse it again.
Status group_selection(EditorState& state);
// Ctrl+Alt+G: removes the groups the selection is in (or is); their nodes become the selection.
Status ungroup_selection(EditorState& state);
// Collapses or expands a group; the selection follows (the group, or its nodes).
Status set_group_collapsed(EditorState& state, const std::string& name, bool collapsed);
// A labelled backdrop around the selection.
Status backdrop_around_selection(EditorState& state, const std::string& label = "Backdrop");

// The viewer shows `output` (any node's any output); the graph's own output is unchanged.
Status select_output(EditorState& state, const PortRef& output);
// The viewer compares the viewed output (A) with `output` (B) in a wipe; nullopt stops.
// Refused when the node or its output does not exist.
Status compare_with(EditorState& state, const std::optional<PortRef>& output);
// Steps the viewer through every output of the graph in node order (+1 or -1).
void cycle_output(EditorState& state, int step);
// Changes what the graph renders (`output` in the file).
Status set_graph_output(EditorState& state, const PortRef& output);

// Files dropped on the window: each image file (png, jpg, exr, tif, hdr, bmp, tga) becomes a
// `read` node at `at` (stacked clear of other nodes), its path relative to the graph's folder
// when it lies under it; the new nodes are selected. Refused when none is an image.
Result<std::vector<std::string>> drop_files(EditorState& state,
                                            const std::vector<std::string>& paths, Position at);

bool undo(EditorState& state);
bool redo(EditorState& state);
Status save(EditorState& state);
// Refused when `path` is another existing file, unless `replace` (the user confirmed).
Status save_as(EditorState& state, const std::string& path, bool replace = false);
Status open(EditorState& state, const std::string& path);
void new_graph(EditorState& state);
void set_frame(EditorState& state, int frame);

// Reports an outcome on the status line.
void report(EditorState& state, const Status& status, const std::string& success);

}  // namespace aq::editor::actions
