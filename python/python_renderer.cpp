// Evaluation and range rendering for the Python module (see python_renderer.h). Messages are
// the command line's ("frame 12: node 'blur' (blur): ...").
#include "python_renderer.h"

#include <aquarelle/core/color.h>
#include <aquarelle/core/display_transform.h>
#include <aquarelle/core/image_io.h>

#include <filesystem>

namespace py = pybind11;

namespace aq::python {

namespace {

// out/####.exr -> out/0012.exr, as `aquarelle render` names frames.
std::string frame_path(const std::string& pattern, int frame) {
  auto start = pattern.find('#');
  if (start == std::string::npos) return pattern;
  auto end = pattern.find_first_not_of('#', start);
  size_t width = (end == std::string::npos ? pattern.size() : end) - start;
  std::string number = std::to_string(frame);
  if (number.size() < width) number.insert(0, width - number.size(), '0');
  return pattern.substr(0, start) + number + (end == std::string::npos ? "" : pattern.substr(end));
}

}  // namespace

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

  int written = 0;
  const int total = last - first + 1;
  for (int frame = first; frame <= last; ++frame) {
    const std::string path = frame_path(output, frame);
    if (!(resume && std::filesystem::exists(path, ec))) {
      EvalOptions options;
      options.frame = frame;
      options.measure_gpu_time = false;
      options.retain_outputs = false;
      auto result = evaluator_->evaluate(graph.graph(), options);
      if (!result.ok()) throw Failure("frame " + std::to_string(frame) + ": " + result.message());
      const aq_image& image = (*result)->image;
      Result<ImageF> pixels = make_error("not read");
      if (transform) {
        auto displayed = transform->apply(image.texture, image.width, image.height);
        if (!displayed.ok()) throw Failure("display transform: " + displayed.message());
        pixels = read_texture(displayed->get(), image.width, image.height, AQ_FORMAT_RGBA32F);
      } else {
        pixels = evaluator_->read_back(*result);
      }
      if (!pixels.ok()) throw Failure("frame " + std::to_string(frame) + ": " + pixels.message());
      if (auto s = write_image(path, *pixels); !s.ok()) {
        throw Failure("frame " + std::to_string(frame) + ": " + s.message());
      }
      ++written;
    }
    if (!progress.is_none()) progress(frame, frame - first + 1, total);
    if (PyErr_CheckSignals() != 0) throw py::error_already_set();  // Ctrl-C between frames
  }
  return written;
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
