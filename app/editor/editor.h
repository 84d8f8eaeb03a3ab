// Entry point of `aquarelle edit`: the GLFW + Dear ImGui graph editor. The command line is
// parsed by app/edit_command.cpp:
//
//   aquarelle edit [GRAPH] [--size WxH] [--script ACTIONS.json] [--screenshot OUT.png] [--quit]
//
// Returns the process exit status.
#pragma once

namespace aq::editor {
struct EditorOptions;
}

int run_editor(const aq::editor::EditorOptions& options);
