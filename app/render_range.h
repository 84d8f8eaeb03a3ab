// The frame loop that `aquarelle render` and the Python module's Renderer.render share:
// evaluate each frame of a range, bring it through the display transform when the output is
// display-referred, write it atomically, skip complete frames on --resume, report each frame
// and stop between frames when asked. Set-up (argument checks, the colour config, the GL
// context) and how a failure is reported stay with the caller.
#pragma once

#include <aquarelle/core/display_transform.h>
#include <aquarelle/core/evaluator.h>
#include <aquarelle/core/graph.h>
#include <aquarelle/core/image.h>
#include <aquarelle/core/image_io.h>
#include <aquarelle/core/result.h>

#include <functional>
#include <optional>
#include <string>

namespace aq::app {

// out/####.exr -> out/0012.exr: the run of `#` becomes the zero-padded frame number.
std::string frame_path(const std::string& pattern, int frame);

struct RangeRequest {
  std::string output;  // file name pattern, `####` for the frame number
  int first = 1, last = 1;
  bool resume = false;  // skip frames whose file exists and reads completely
  // Per-frame evaluation options; `frame` is set by the loop.
  EvalOptions eval;
  WriteOptions write;
  // Display-referred outputs go through it; nullptr writes the evaluator's linear pixels.
  const DisplayTransform* transform = nullptr;
};

// What happened to one frame, for progress reports and per-frame bookkeeping.
struct FrameReport {
  int frame = 0;
  int done = 0;          // frames handled so far, this one included
  int total = 0;         // frames in the range
  bool skipped = false;  // --resume found it complete
};

struct RangeHooks {
  // Asked before each frame; true stops the range (RangeOutcome::interrupted).
  std::function<bool()> stop_requested;
  // Refuses a frame's path before it is rendered (an output that is an input file).
  std::function<Status(const std::string& path)> check_path;
  // Writes a frame's pixels; unset: write_image(path, pixels, request.write).
  std::function<Status(const std::string& path, const EvalOptions& options, const ImageF& pixels)>
      write_frame;
  // After each frame, written or skipped.
  std::function<void(const FrameReport&)> frame_done;
};

struct RangeFailure {
  // Bad input (the graph, a path, a file that cannot be written) or the environment (GL,
  // the display transform): the command line's exit codes 1 and 2.
  bool environment = false;
  std::string message;  // "frame 12: node 'blur' (blur): ..."
};

struct RangeOutcome {
  int written = 0;
  int skipped = 0;
  bool interrupted = false;
  std::optional<RangeFailure> failure;  // the range stopped at the failing frame
};

RangeOutcome render_range(Evaluator& evaluator, const Graph& graph, const RangeRequest& request,
                          const RangeHooks& hooks);

}  // namespace aq::app
