// What the editor's views share besides the document: the selection, the output shown in the
// viewer, the canvas view, the current frame and the status line. Views read it; they change
// it and the document only through editor_actions.h, the same functions the scripted mode calls.
#pragma once

#include "canvas_view.h"
#include "document.h"

#include <aquarelle/core/graph.h>

#include <optional>
#include <set>
#include <string>

namespace aq::editor {

struct EditorState {
  explicit EditorState(Document& document) : doc(document) {}

  Document& doc;
  std::set<std::string> selection;
  // The output shown in the viewer; nullopt shows the graph's output.
  std::optional<PortRef> viewed;
  // B of the viewer's A/B wipe: another output evaluated beside the viewed one (A); nullopt:
  // no compare of two outputs.
  std::optional<PortRef> compare;
  CanvasView canvas;
  int frame = 1;
  bool playing = false;

  std::string status;  // last action's result, shown in the status bar
  bool status_is_error = false;
  // The last refused edit with its reason, for the scripted mode's exit status.
  int refused_count = 0;

  // The output the viewer evaluates: `viewed` when it still exists, else the graph's output.
  std::optional<PortRef> shown_output() const;
};

}  // namespace aq::editor
