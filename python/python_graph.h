// The graph side of the Python module: the installed node types (loaded once per process) and
// PyGraph, a graph model edited with the command line's checks. Failures are C++ exceptions
// that the module turns into aquarelle.Error / aquarelle.GraphError.
#pragma once

#include <pybind11/pybind11.h>

#include <aquarelle/core/graph.h>
#include <aquarelle/core/graph_io.h>
#include <aquarelle/core/message_text.h>
#include <aquarelle/core/registry.h>

#include <map>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace aq::python {

// One-line messages: control characters in them (a name holding a newline or ESC) are
// escaped, as in every message of the command line.
struct Failure : std::runtime_error {
  explicit Failure(const std::string& message) : std::runtime_error(escape_for_message(message)) {}

 protected:
  struct Lines {};
  Failure(const std::string& message, Lines)
      : std::runtime_error(escape_for_message(message, true)) {}
};
// An invalid graph: the message lists every problem (one a line), `problems` keeps them.
struct GraphFailure : Failure {
  GraphFailure(const std::vector<Problem>& list)
      : Failure(format_problems(list), Lines{}), problems(list) {}
  std::vector<Problem> problems;
};

// Built-in types and every plugin of the plugin path: AQUARELLE_PLUGIN_PATH, then the plugins
// installed beside the module (cmake --install) or else the build's. Loaded on first use and
// kept for the life of the process (plugin code must stay mapped while nodes exist).
const Registry& registry();
// The folders plugins load from, in order.
std::vector<std::string> plugin_path();

std::vector<const NodeType*> node_types();
const NodeType& node_type(const std::string& name);
std::vector<Problem> validate_file(const std::string& path);
pybind11::object default_value(const ParamInfo& param);

class PyGraph {
 public:
  static PyGraph load(const std::string& path);
  static PyGraph from_json(const std::string& text, const std::string& file);
  void save(const std::string& path) const;
  std::string to_json() const { return write_graph_text(graph_); }
  std::vector<Problem> problems() const;
  // Throws GraphFailure when the graph as edited is invalid (before rendering).
  void check() const;

  std::map<std::string, std::string> nodes() const;
  std::map<std::string, std::string> inputs(const std::string& node) const;
  pybind11::dict params(const std::string& node) const;
  pybind11::object get(const std::string& node, const std::string& param) const;
  void set(const std::string& node, const std::string& param, const pybind11::object& value);
  void link(const std::string& source, const std::string& target);
  void unlink(const std::string& target);
  void add_node(const std::string& id, const std::string& type);
  void remove_node(const std::string& id);
  // Nuke's disable: the node passes its first input through, in the render as in the editor.
  bool bypass(const std::string& id) const;
  void set_bypass(const std::string& id, bool bypass);

  std::string output() const { return graph_.output ? graph_.output->str() : ""; }
  void set_output(const std::string& port);
  int width() const { return graph_.settings.width; }
  void set_width(int width);
  int height() const { return graph_.settings.height; }
  void set_height(int height);
  std::pair<int, int> frames() const {
    return {graph_.settings.first_frame, graph_.settings.last_frame};
  }
  void set_frames(std::pair<int, int> frames);
  double fps() const { return graph_.settings.fps; }
  void set_fps(double fps) { graph_.settings.fps = fps; }
  std::string precision() const { return graph_.settings.precision; }
  void set_precision(const std::string& precision);
  std::string quality() const { return graph_.settings.quality; }
  void set_quality(const std::string& quality);
  std::string path() const { return graph_.source_path; }

  const Graph& graph() const { return graph_; }

 private:
  const Node& node(const std::string& id) const;
  Graph graph_;
};

}  // namespace aq::python
