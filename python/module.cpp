// `import aquarelle`: the core library from Python (pybind11). Graphs are read, validated,
// edited and saved; node types are listed with their ports and parameters; a Renderer owns a
// headless GL context and evaluates any node output of a frame into a NumPy array (float32,
// H x W x 4, row 0 at the top, as image libraries expect) or renders a range of frames with a
// progress callback. Errors raise aquarelle.Error (a RuntimeError) with the command line's
// message; an invalid graph raises aquarelle.GraphError carrying its problems.
#include <pybind11/functional.h>
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <aquarelle/core/color.h>
#include <aquarelle/core/graph_io.h>
#include <aquarelle/core/image_io.h>
#include <aquarelle/core/write_guard.h>

#include "python_graph.h"
#include "python_renderer.h"
#include "session.h"

namespace py = pybind11;

namespace aq::python {

namespace {

py::object problem_list(const std::vector<Problem>& problems) {
  py::list list;
  for (const auto& p : problems) list.append(py::cast(p));
  return list;
}

// Float pixels (row 0 at the bottom, 1 or 4 channels) as an H x W x 4 float32 array with row
// 0 at the top; one-channel images (depth, ids) fill R, G and B, with alpha 1.
py::array_t<float> to_array(const ImageF& image) {
  py::array_t<float> array({image.height, image.width, 4});
  auto out = array.mutable_unchecked<3>();
  for (int y = 0; y < image.height; ++y) {
    const int row = image.height - 1 - y;
    for (int x = 0; x < image.width; ++x) {
      for (int c = 0; c < 4; ++c) {
        const int source = image.channels == 1 ? 0 : c;
        out(y, x, c) = image.channels == 1 && c == 3 ? 1.0f : image.at(x, row, source);
      }
    }
  }
  return array;
}

ImageF from_array(const py::array_t<float, py::array::c_style | py::array::forcecast>& array) {
  if (array.ndim() != 3 || (array.shape(2) != 1 && array.shape(2) != 3 && array.shape(2) != 4)) {
    throw Failure("expected an array of shape (height, width, 1|3|4), got " +
                  std::string(py::str(array.attr("shape"))));
  }
  const int height = static_cast<int>(array.shape(0)), width = static_cast<int>(array.shape(1)),
            channels = static_cast<int>(array.shape(2));
  ImageF image(width, height, channels);
  auto in = array.unchecked<3>();
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) {
      for (int c = 0; c < channels; ++c) image.at(x, height - 1 - y, c) = in(y, x, c);
    }
  }
  return image;
}

// aquarelle.Error (a RuntimeError) and aquarelle.GraphError carrying .problems.
void bind_errors(py::module_& m) {
  static py::exception<Failure> error(m, "Error", PyExc_RuntimeError);
  static py::exception<GraphFailure> graph_error(m, "GraphError", error.ptr());
  py::register_exception_translator([](std::exception_ptr thrown) {
    try {
      if (thrown) std::rethrow_exception(thrown);
    } catch (const GraphFailure& failure) {
      py::object instance = py::handle(graph_error.ptr())(failure.what());
      instance.attr("problems") = problem_list(failure.problems);
      PyErr_SetObject(graph_error.ptr(), instance.ptr());
    } catch (const Failure& failure) {
      error(failure.what());
    }
  });
}

// Problem, Port, Param and NodeType: read-only descriptions.
void bind_descriptions(py::module_& m) {
  py::class_<Problem>(m, "Problem", "A located problem of a graph file")
      .def_readonly("file", &Problem::file)
      .def_readonly("line", &Problem::line)
      .def_readonly("column", &Problem::column)
      .def_readonly("pointer", &Problem::pointer)
      .def_readonly("node", &Problem::node)
      .def_property_readonly(
          "parameter", [](const Problem& p) { return p.field; },
          "the port, parameter or settings key")
      .def_readonly("message", &Problem::message)
      .def("__str__", &format_problem)
      .def("__repr__",
           [](const Problem& p) { return "<aquarelle.Problem " + format_problem(p) + ">"; });

  py::class_<PortInfo>(m, "Port")
      .def_readonly("name", &PortInfo::name)
      .def_property_readonly("type", [](const PortInfo& p) { return port_type_name(p.type); })
      .def_readonly("optional", &PortInfo::optional)
      .def_readonly("description", &PortInfo::description)
      .def("__repr__", [](const PortInfo& p) {
        return "<aquarelle.Port " + p.name + ": " + port_type_name(p.type) + ">";
      });
  py::class_<ParamInfo>(m, "Param")
      .def_readonly("name", &ParamInfo::name)
      .def_property_readonly("type", [](const ParamInfo& p) { return param_type_name(p.type); })
      .def_property_readonly("default", [](const ParamInfo& p) { return default_value(p); })
      .def_readonly("min", &ParamInfo::min_value)
      .def_readonly("max", &ParamInfo::max_value)
      .def_readonly("choices", &ParamInfo::enum_values)
      .def_readonly("description", &ParamInfo::description)
      .def("__repr__", [](const ParamInfo& p) {
        return "<aquarelle.Param " + p.name + ": " + param_type_name(p.type) + ">";
      });
  py::class_<NodeType>(m, "NodeType")
      .def_readonly("name", &NodeType::name)
      .def_readonly("category", &NodeType::category)
      .def_readonly("description", &NodeType::description)
      .def_readonly("inputs", &NodeType::inputs)
      .def_readonly("outputs", &NodeType::outputs)
      .def_readonly("params", &NodeType::params)
      .def_property_readonly("time_dependent", &NodeType::time_dependent)
      .def_property_readonly("pointwise", &NodeType::pointwise)
      .def("__repr__", [](const NodeType& t) { return "<aquarelle.NodeType " + t.name + ">"; });
}

// The installed node types, the plugin path and file validation.
void bind_registry(py::module_& m) {
  m.def("node_types", &node_types, py::return_value_policy::reference,
        "Every installed node type (built in and plugins), by name");
  m.def("node_type", &node_type, py::arg("name"), py::return_value_policy::reference,
        "One node type; Error naming the installed types when there is none");
  m.def("plugin_path", &plugin_path, "The folders node plugins are loaded from");
  m.def(
      "validate_file", [](const std::string& path) { return validate_file(path); }, py::arg("path"),
      "Every problem of a graph file (an empty list when it is valid)");
}

// Graph: reading, editing with the command line's checks, saving.
void bind_graph(py::module_& m) {
  py::class_<PyGraph>(m, "Graph", "A graph: nodes, links, parameters, settings and output")
      .def_static("load", &PyGraph::load, py::arg("path"),
                  "Reads a graph file; GraphError with .problems when it is invalid")
      .def_static("from_json", &PyGraph::from_json, py::arg("text"), py::arg("file") = "")
      .def("save", &PyGraph::save, py::arg("path"), "Canonical JSON, written atomically")
      .def("to_json", &PyGraph::to_json)
      .def("problems", &PyGraph::problems, "Validates the graph as edited (list of Problem)")
      .def_property_readonly("nodes", &PyGraph::nodes, "{node id: type name}")
      .def("inputs", &PyGraph::inputs, py::arg("node"), "{input port: 'source.port'}")
      .def("params", &PyGraph::params, py::arg("node"),
           "{parameter: value} with defaults filled in")
      .def("get", &PyGraph::get, py::arg("node"), py::arg("param"))
      .def("set", &PyGraph::set, py::arg("node"), py::arg("param"), py::arg("value"),
           "Sets a parameter, checked like --set NODE.PARAM=VALUE")
      .def("link", &PyGraph::link, py::arg("source"), py::arg("target"),
           "Connects 'node.output' to 'node.input'")
      .def("unlink", &PyGraph::unlink, py::arg("target"), "Disconnects 'node.input'")
      .def("add_node", &PyGraph::add_node, py::arg("id"), py::arg("type"))
      .def("remove_node", &PyGraph::remove_node, py::arg("id"))
      .def("bypass", &PyGraph::bypass, py::arg("node"), "Whether the node is bypassed")
      .def("set_bypass", &PyGraph::set_bypass, py::arg("node"), py::arg("bypass") = true,
           "Bypass (Nuke's disable) or enable a node: it passes its first input through")
      .def_property("output", &PyGraph::output, &PyGraph::set_output)
      .def_property("width", &PyGraph::width, &PyGraph::set_width)
      .def_property("height", &PyGraph::height, &PyGraph::set_height)
      .def_property("frames", &PyGraph::frames, &PyGraph::set_frames)
      .def_property("fps", &PyGraph::fps, &PyGraph::set_fps)
      .def_property("precision", &PyGraph::precision, &PyGraph::set_precision)
      .def_property("quality", &PyGraph::quality, &PyGraph::set_quality)
      .def_property_readonly("path", &PyGraph::path);
}

// Renderer: a headless GL context that evaluates and renders.
void bind_renderer(py::module_& m) {
  py::class_<PyRenderer>(m, "Renderer", "A headless GL context with an evaluator")
      .def(py::init<const std::string&, const std::string&>(), py::arg("gl") = "auto",
           py::arg("device") = "auto")
      .def_property_readonly("description", &PyRenderer::description)
      .def(
          "evaluate",
          [](PyRenderer& self, const PyGraph& graph, int frame, const std::string& output) {
            return to_array(self.evaluate(graph, frame, output));
          },
          py::arg("graph"), py::arg("frame") = 1, py::arg("output") = "",
          "A node output ('node.port', default the graph's output) at `frame` as float32 "
          "H x W x 4, row 0 at the top; scene-linear")
      .def("render", &PyRenderer::render, py::arg("graph"), py::arg("output"),
           py::arg("frames") = py::none(), py::arg("progress") = py::none(),
           py::arg("resume") = false,
           "Renders frames (first, last) to OUTPUT with #### for the frame number, like "
           "`aquarelle render`; progress(frame, done, total) after each frame. Returns the "
           "number of frames written")
      .def("last_timings", &PyRenderer::last_timings,
           "[(node, type, gpu ms, cpu ms, cached)] of the last evaluation");
}

// Image files as NumPy arrays; writing goes through the shared write guard.
void bind_images(py::module_& m) {
  m.def(
      "read_image",
      [](const std::string& path) {
        auto config = ColorConfig::load();
        if (!config.ok()) throw Failure(config.message());
        auto image = read_image(path, *config);
        if (!image.ok()) throw Failure(image.message());
        return to_array(*image);
      },
      py::arg("path"), "An image file as float32 H x W x 4 in the working space, row 0 at the top");
  m.def(
      "write_image",
      [](const std::string& path,
         const py::array_t<float, py::array::c_style | py::array::forcecast>& pixels,
         bool float_data) {
        if (auto s = check_may_write("write_image", path); !s.ok()) throw Failure(s.message());
        WriteOptions options;
        options.float_data = float_data;
        if (auto s = write_image(path, from_array(pixels), options); !s.ok()) {
          throw Failure(s.message());
        }
      },
      py::arg("path"), py::arg("pixels"), py::arg("float_data") = false,
      "Writes H x W x 1|3|4 float pixels (row 0 at the top) atomically: EXR keeps them linear; "
      "PNG/JPEG/TIFF store them as display values in [0, 1]");
}

}  // namespace

PYBIND11_MODULE(aquarelle, m) {
  m.doc() =
      "Aquarelle: node-graph compositor for stylized rendering. Read and edit graphs, list node "
      "types, evaluate any node output as a NumPy array, render frame ranges.";
  bind_errors(m);
  bind_descriptions(m);
  bind_registry(m);
  bind_graph(m);
  bind_renderer(m);
  bind_images(m);
}

}  // namespace aq::python
