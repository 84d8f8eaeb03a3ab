// The rendering side of the Python module: a headless GL context and an evaluator, evaluating
// any node output of a frame or rendering a frame range to files as `aquarelle render` does
// (atomic frames, EXR linear, display formats through the OCIO view, --resume).
#pragma once

#include <pybind11/pybind11.h>

#include <aquarelle/core/evaluator.h>
#include <aquarelle/core/gl_context.h>

#include <memory>
#include <optional>
#include <string>
#include <tuple>
#include <vector>

#include "python_graph.h"

namespace aq::python {

class PyRenderer {
 public:
  PyRenderer(const std::string& gl, const std::string& device);
  ~PyRenderer();

  std::string description() const { return context_->description(); }
  ImageF evaluate(const PyGraph& graph, int frame, const std::string& output);
  int render(const PyGraph& graph, const std::string& output,
             const std::optional<std::pair<int, int>>& frames, const pybind11::object& progress,
             bool resume);
  std::vector<std::tuple<std::string, std::string, double, double, bool>> last_timings() const;

 private:
  std::unique_ptr<GlContext> context_;
  std::unique_ptr<Evaluator> evaluator_;
};

}  // namespace aq::python
