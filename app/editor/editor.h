// Entry point of `aquarelle edit`: the GLFW + Dear ImGui graph editor.
//
//   aquarelle edit [GRAPH] [--size WxH] [--script ACTIONS.json] [--screenshot OUT.png] [--quit]
//
// argv[0] is "edit"; the rest are the editor's arguments. Returns the process exit status.
#pragma once

int run_editor(int argc, char** argv);
