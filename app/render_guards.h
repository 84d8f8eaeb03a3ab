// What `aquarelle render` checks and arranges before and around rendering so that bad input
// and signals end it cleanly: a GL probe in a child process (a broken driver crashes the
// child, not us), outputs that would overwrite the graph or an input file, prompt stops on
// SIGINT/SIGTERM even inside a long node, and --resume housekeeping.
#pragma once

#include <aquarelle/core/gl_context.h>
#include <aquarelle/core/graph.h>
#include <aquarelle/core/registry.h>
#include <aquarelle/core/result.h>
#include <aquarelle/core/write_guard.h>

#include <string>
#include <vector>

namespace aq::app {

// Creates the headless context in a forked child first. Ok when the child managed or failed
// with an ordinary error (the caller then creates it and reports that error); an error when
// the child crashed (a signal in the driver) or hung, naming the backend, the signal and the
// driver environment to check. Call it before plugins load: the child only creates a context
// (glibc's malloc is fork-safe; the few threads libraries start at load hold no other locks
// the child needs). Costs about 40 ms (one extra context on llvmpipe).
Status probe_gl_in_child(GlBackend backend, const std::string& device);

// Every file the render reads (aq::files_read_by, with the colour config and its LUTs).
std::vector<ReadFile> graph_input_files(const Graph& graph, const Registry& registry);

// Refuses writing a frame's file, or its layers' side file (`layers_file`, empty when none),
// onto a file the render reads or onto something that is not a regular file
// (aq::check_may_write: the same file through any link or relative spelling).
Status check_frame_outputs(const std::string& frame_file, const std::string& layers_file,
                           const std::vector<ReadFile>& reads);

// SIGINT/SIGTERM: the render loop stops between frames when it can; when a node or a file
// load does not return within kStopGraceSeconds the process ends at once with exit code 130
// (every frame file is written atomically, so nothing half-written is left under its name).
// A second signal ends it at once.
inline constexpr unsigned kStopGraceSeconds = 1;
void install_stop_handlers();
bool stop_requested();
// The loop has stopped on its own: no forced exit any more.
void cancel_forced_stop();

}  // namespace aq::app
