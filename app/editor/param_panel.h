// The parameter panel, built from the selected node type's parameter descriptions: sliders
// with the declared ranges (logarithmic when hinted), colour pickers, enum combos, text fields
// and file pickers for paths; right-click resets to the default. Each edit goes through
// actions::set_param; a drag is one undo step. With no single node selected it shows the
// graph's settings instead.
#pragma once

#include "canvas.h"
#include "editor_state.h"
#include "file_dialog.h"

#include <optional>
#include <string>

namespace aq::editor {

class ParamPanel {
 public:
  void draw(EditorState& state, const NodeFeedback& feedback);

 private:
  void draw_node(EditorState& state, const std::string& id, const NodeFeedback& feedback);
  void draw_params(EditorState& state, const std::string& id, const NodeType& type);
  void draw_settings(EditorState& state);
  // A collapsed group: its nodes as a list; the parameters of the one picked.
  void draw_group(EditorState& state, const std::string& name, const NodeFeedback& feedback);

  std::string group_member_;  // the group's node whose parameters are shown
  FileDialog file_dialog_;
  std::string file_target_;
  std::optional<Settings> pending_settings_;  // "node\nparam" the open file dialog writes to
};

}  // namespace aq::editor
