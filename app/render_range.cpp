// The shared frame loop of `aquarelle render` and the Python module (see render_range.h).
#include "render_range.h"

#include <aquarelle/core/graph_io.h>

#include <cstdio>
#include <filesystem>

namespace aq::app {

std::string frame_path(const std::string& pattern, int frame) {
  auto start = pattern.find('#');
  if (start == std::string::npos) return pattern;
  auto end = pattern.find_first_not_of('#', start);
  size_t width = (end == std::string::npos ? pattern.size() : end) - start;
  char number[32];
  std::snprintf(number, sizeof(number), "%0*d", static_cast<int>(width), frame);
  return pattern.substr(0, start) + number + (end == std::string::npos ? "" : pattern.substr(end));
}

RangeOutcome render_range(Evaluator& evaluator, const Graph& graph, const RangeRequest& request,
                          const RangeHooks& hooks) {
  RangeOutcome outcome;
  auto fail = [&](bool environment, const std::string& message) {
    outcome.failure = RangeFailure{environment, message};
    return outcome;
  };
  auto at = [](int frame) { return "frame " + std::to_string(frame) + ": "; };
  // Checked here too (callers may build a request by hand): a range ending at INT_MAX would
  // wrap and never end.
  if (std::string why = frame_range_problem(request.first, request.last); !why.empty()) {
    return fail(false, "frames " + std::to_string(request.first) + "-" +
                           std::to_string(request.last) + ": " + why);
  }
  const int total = request.last - request.first + 1;
  std::error_code ec;
  for (int frame = request.first; frame <= request.last; ++frame) {
    if (hooks.stop_requested && hooks.stop_requested()) {
      outcome.interrupted = true;
      break;
    }
    const std::string path = frame_path(request.output, frame);
    if (hooks.check_path) {
      if (auto s = hooks.check_path(path); !s.ok()) return fail(false, at(frame) + s.message());
    }
    const int done = frame - request.first + 1;
    if (request.resume) {
      remove_stale_temporaries(path);
      // A truncated frame (a copy cut short, a full disk under another tool) is rendered again.
      if (std::filesystem::exists(path, ec) && is_complete_image(path)) {
        ++outcome.skipped;
        if (hooks.frame_done) hooks.frame_done(FrameReport{frame, done, total, true});
        continue;
      }
    }
    EvalOptions options = request.eval;
    options.frame = frame;
    auto result = evaluator.evaluate(graph, options);
    if (!result.ok()) return fail(false, at(frame) + result.message());
    const aq_image& image = (*result)->image;
    Result<ImageF> pixels = make_error("not read");
    if (request.transform != nullptr) {
      auto displayed = request.transform->apply(image.texture, image.width, image.height);
      if (!displayed.ok()) return fail(true, "display transform: " + displayed.message());
      pixels = read_texture(displayed->get(), image.width, image.height, AQ_FORMAT_RGBA32F);
    } else {
      pixels = evaluator.read_back(*result);
    }
    if (!pixels.ok()) return fail(true, at(frame) + pixels.message());
    Status written = hooks.write_frame ? hooks.write_frame(path, options, *pixels)
                                       : write_image(path, *pixels, request.write);
    if (!written.ok()) return fail(false, at(frame) + written.message());
    ++outcome.written;
    if (hooks.frame_done) hooks.frame_done(FrameReport{frame, done, total, false});
  }
  return outcome;
}

}  // namespace aq::app
