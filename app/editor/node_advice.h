// What is wrong with a node and how to fix it, in the editor's terms: one list, shown the same
// in the node's tooltip on the canvas and in the parameter panel (the panel used to tell the
// user to edit the JSON, the tooltip to drag a link). No GL.
#pragma once

#include "document.h"

#include <string>
#include <vector>

namespace aq::editor {

// The node's type not being installed, its validation problems and the last evaluation's
// error when it names this node (`evaluation_error`, "" when none), each once.
std::vector<std::string> node_advice(const Document& doc, const std::string& id,
                                     const std::string& evaluation_error);

}  // namespace aq::editor
