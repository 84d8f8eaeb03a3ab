// Evaluation and range rendering for the Python module (see python_renderer.h). Messages are
// the command line's ("frame 12: node 'blur' (blur): ...").
#include "python_renderer.h"

#include <aquarelle/core/color.h>
#include <aquarelle/core/display_transform.h>
#include <aquarelle/core/image_io.h>
#include <aquarelle/core/write_guard.h>

#include <filesystem>

#include "render_range.h"

namespace py = pybind11;

namespace aq::python {

using app::frame_path;

PyRenderer::PyRenderer(const std::string& gl, const std::string& device) {
  auto backend = parse_backend(gl);
  if (!backend.ok()) throw Failure("gl: " + backend.message());
  if (auto s = check_gl_device(device); !s.ok()) throw Failure("device: " + s.message());
  auto context = create_headless_context(*backend, device);
  if (!context.ok()) throw Failure(context.message());
  context_ = std::move(*context);
  evaluator_ = std::make_unique<Evaluator>(*context_, registry());
}

PyRenderer::~PyRenderer() {
  evaluator_.reset();  // node instances and textures go while their context exists
}

ImageF PyRenderer::evaluate(const PyGraph& graph, int frame, const std::string& output) {
  graph.check();
  std::optional<PortRef> port;
  if (!output.empty()) {
    port = PortRef::parse(output);
    if (!port) throw Failure("output '" + output + "': expected 'node.port', e.g. 'gbuf.normal'");
  }
  EvalOptions options;
  options.frame = frame;
  options.measure_gpu_time = false;
  auto texture = evaluator_->evaluate(graph.graph(), options, port);
  if (!texture.ok()) throw Failure("frame " + std::to_string(frame) + ": " + texture.message());
  auto pixels = evaluator_->read_back(*texture);
  if (!pixels.ok()) throw Failure("frame " + std::to_string(frame) + ": " + pixels.message());
  return std::move(*pixels);
}

int PyRenderer::render(const PyGraph& graph, const std::string& output,
                       const std::optional<std::pair<int, int>>& frames, const py::object& progress,
                       bool resume) {
  graph.check();
  const Settings& settings = graph.graph().settings;
  const auto [first, last] =
      frames.value_or(std::pair<int, int>{settings.first_frame, settings.last_frame});
  if (first > last) {
    throw Failure("frames (" + std::to_string(first) + ", " + std::to_string(last) +
                  "): the first frame is after the last");
  }
  if (last > first && output.find('#') == std::string::npos) {
    throw Failure("rendering frames " + std::to_string(first) + "-" + std::to_string(last) +
                  " needs `####` in the output name for the frame number, e.g. out/####.png");
  }
  std::error_code ec;
  auto out_dir = std::filesystem::path(frame_path(output, first)).parent_path();
  if (!out_dir.empty() && !std::filesystem::is_directory(out_dir, ec)) {
    throw Failure("output folder '" + out_dir.string() + "' does not exist: create it first");
  }
  std::optional<DisplayTransform> transform;
  if (is_display_referred_format(frame_path(output, first))) {
    auto color = ColorConfig::load();
    if (!color.ok()) throw Failure(color.message());
    auto t = DisplayTransform::create(*color, "", "");
    if (!t.ok()) throw Failure(t.message());
    transform = std::move(*t);
  }
  struct ReleaseTransform {
    std::optional<DisplayTransform>& transform;
    GlContext& context;
    ~ReleaseTransform() {
      if (transform && context.activate()) transform->release_gl();
    }
  } release{transform, *context_};

  app::RangeRequest request;
  request.output = output;
  request.first = first;
  request.last = last;
  request.resume = resume;
  request.eval.measure_gpu_time = false;
  request.eval.retain_outputs = false;
  request.transform = transform ? &*transform : nullptr;
  app::RangeHooks hooks;
  // The command line's rule: never write onto a file the graph reads, nor onto a FIFO.
  auto color = ColorConfig::load();
  const std::vector<ReadFile> reads =
      files_read_by(graph.graph(), registry(), color.ok() ? &*color : nullptr);
  if (auto s = check_may_write("output", frame_path(output, first), reads); !s.ok()) {
    throw Failure(s.message());
  }
  hooks.check_path = [&](const std::string& path) {
    return check_may_write("output", path, reads);
  };
  // Ctrl-C between frames: the pending KeyboardInterrupt is raised once the range stops.
  hooks.stop_requested = [] { return PyErr_CheckSignals() != 0; };
  if (!progress.is_none()) {
    hooks.frame_done = [&](const app::FrameReport& report) {
      progress(report.frame, report.done, report.total);
    };
  }
  const app::RangeOutcome outcome = app::render_range(*evaluator_, graph.graph(), request, hooks);
  if (outcome.failure) throw Failure(outcome.failure->message);
  if (outcome.interrupted || PyErr_CheckSignals() != 0) throw py::error_already_set();
  return outcome.written;
}

std::vector<std::tuple<std::string, std::string, double, double, bool>> PyRenderer::last_timings()
    const {
  std::vector<std::tuple<std::string, std::string, double, double, bool>> out;
  for (const auto& t : evaluator_->last_timings()) {
    out.emplace_back(t.node, t.type, t.gpu_ms, t.cpu_ms, t.cached);
  }
  return out;
}

}  // namespace aq::python
