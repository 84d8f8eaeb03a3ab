// Node types and graph editing for the Python module (see python_graph.h).
#include "python_graph.h"

#include "python_values.h"

#include <pybind11/stl.h>

#include <aquarelle/core/plugin_loader.h>

#include <dlfcn.h>

#include <cstdlib>
#include <filesystem>

#include "session.h"

namespace py = pybind11;
namespace fs = std::filesystem;

namespace aq::python {

namespace {

struct LoadedPlugins {
  Registry registry;
  PluginSet set;
};

// The folder this module was loaded from.
fs::path module_dir() {
  Dl_info info{};
  if (dladdr(reinterpret_cast<void*>(&module_dir), &info) == 0 || info.dli_fname == nullptr) {
    return {};
  }
  return fs::path(info.dli_fname).parent_path();
}

}  // namespace

std::vector<std::string> plugin_path() {
  std::vector<std::string> path = plugin_path_from_environment();
  // Installed: the plugins sit at a fixed place relative to the module (set by CMake).
  std::error_code ec;
  const fs::path installed = (module_dir() / AQ_PYTHON_TO_PLUGINS).lexically_normal();
  path.push_back(fs::is_directory(installed, ec) ? installed.string() : AQ_PLUGIN_BUILD_DIR);
  return path;
}

namespace {

py::object from_json(const nlohmann::json& value) {
  if (value.is_null()) return py::none();
  if (value.is_boolean()) return py::bool_(value.get<bool>());
  if (value.is_number_integer()) return py::int_(value.get<int64_t>());
  if (value.is_number()) return py::float_(value.get<double>());
  if (value.is_string()) return py::str(value.get<std::string>());
  if (value.is_array()) {
    py::list list;
    for (const auto& item : value) list.append(from_json(item));
    return list;
  }
  py::dict dict;
  for (const auto& [key, item] : value.items()) dict[py::str(key)] = from_json(item);
  return dict;
}

void check_status(const Status& status) {
  if (!status.ok()) throw Failure(status.message());
}

}  // namespace

const Registry& registry() {
  // Never destroyed: node instances of plugins may outlive any static destructor order.
  static LoadedPlugins* plugins = [] {
    auto* loaded = new LoadedPlugins;
    register_builtin_nodes(loaded->registry);
    auto path = plugin_path();
    auto report = loaded->set.load(path, loaded->registry);
    if (report.loaded.empty()) {
      std::string searched;
      for (const auto& dir : path) searched += "\n  " + dir;
      delete loaded;
      throw Failure("no plugin could be loaded from the plugin path:" + searched +
                    "\nBuild the project (cmake --build build) or set AQUARELLE_PLUGIN_PATH to a "
                    "folder of aquarelle_*.so plugins.");
    }
    return loaded;
  }();
  return plugins->registry;
}

std::vector<const NodeType*> node_types() {
  std::vector<const NodeType*> types;
  for (const auto& [name, type] : registry().types()) types.push_back(&type);
  return types;
}

const NodeType& node_type(const std::string& name) {
  const NodeType* type = registry().find(name);
  if (type == nullptr) {
    std::string names;
    for (const auto& n : registry().names()) names += (names.empty() ? "" : ", ") + n;
    throw Failure("unknown node type '" + name + "' (installed: " + names + ")");
  }
  return *type;
}

std::vector<Problem> validate_file(const std::string& path) {
  return read_graph_file(path, registry()).problems;
}

py::object default_value(const ParamInfo& p) {
  switch (p.type) {
    case AQ_PARAM_FLOAT:
      return py::float_(p.default_value[0]);
    case AQ_PARAM_INT:
      return py::int_(static_cast<int64_t>(p.default_value[0]));
    case AQ_PARAM_BOOL:
      return py::bool_(p.default_value[0] != 0);
    case AQ_PARAM_ENUM: {
      const auto index = static_cast<size_t>(p.default_value[0]);
      return index < p.enum_values.size() ? py::object(py::str(p.enum_values[index]))
                                          : py::object(py::none());
    }
    case AQ_PARAM_COLOR:
    case AQ_PARAM_VEC3:
      return py::make_tuple(p.default_value[0], p.default_value[1], p.default_value[2]);
    case AQ_PARAM_STRING:
    case AQ_PARAM_PATH:
      return py::str(p.default_string);
  }
  return py::none();
}

PyGraph PyGraph::load(const std::string& path) {
  ReadResult read = read_graph_file(path, registry());
  if (!read.ok()) throw GraphFailure(read.problems);
  PyGraph graph;
  graph.graph_ = std::move(read.graph);
  return graph;
}

PyGraph PyGraph::from_json(const std::string& text, const std::string& file) {
  ReadResult read = read_graph_text(text, registry(), file);
  if (!read.ok()) throw GraphFailure(read.problems);
  PyGraph graph;
  graph.graph_ = std::move(read.graph);
  return graph;
}

void PyGraph::save(const std::string& path) const {
  check_status(save_graph_file(graph_, path));
}

std::vector<Problem> PyGraph::problems() const {
  auto problems = validate_graph(graph_, registry());
  for (auto& p : problems) p.file = graph_.source_path;
  return problems;
}

void PyGraph::check() const {
  if (auto list = problems(); !list.empty()) throw GraphFailure(list);
}

const Node& PyGraph::node(const std::string& id) const {
  auto found = graph_.nodes.find(id);
  if (found == graph_.nodes.end()) {
    std::string ids;
    for (const auto& [n, node] : graph_.nodes) ids += (ids.empty() ? "" : ", ") + n;
    throw Failure("no node '" + id + "' in the graph (nodes: " + ids + ")");
  }
  return found->second;
}

std::map<std::string, std::string> PyGraph::nodes() const {
  std::map<std::string, std::string> out;
  for (const auto& [id, n] : graph_.nodes) out[id] = n.type;
  return out;
}

std::map<std::string, std::string> PyGraph::inputs(const std::string& id) const {
  std::map<std::string, std::string> out;
  for (const auto& [port, source] : node(id).inputs) out[port] = source.str();
  return out;
}

py::dict PyGraph::params(const std::string& id) const {
  const Node& n = node(id);
  py::dict out;
  if (const NodeType* type = registry().find(n.type); type != nullptr) {
    for (const auto& p : type->params) {
      out[py::str(p.name)] = aq::python::from_json(param_value_or_default(n, p));
    }
  }
  return out;
}

py::object PyGraph::get(const std::string& id, const std::string& param) const {
  const Node& n = node(id);
  const NodeType& type = node_type(n.type);
  const ParamInfo* info = type.param(param);
  if (info == nullptr) {
    std::string names;
    for (const auto& p : type.params) names += (names.empty() ? "" : ", ") + p.name;
    throw Failure("node '" + id + "' (" + type.name + ") has no parameter '" + param +
                  "' (parameters: " + names + ")");
  }
  return aq::python::from_json(param_value_or_default(n, *info));
}

void PyGraph::set(const std::string& id, const std::string& param, const py::object& value) {
  // The command line's --set, so the checks and messages are the same.
  const nlohmann::json converted = parameter_value_from_python(
      value, "node " + quote_for_message(id) + ", parameter " + quote_for_message(param));
  const std::string assignment = id + "." + param + "=" + converted.dump();
  std::optional<nlohmann::json> previous;
  if (auto found = graph_.nodes.find(id); found != graph_.nodes.end()) {
    if (auto it = found->second.params.find(param); it != found->second.params.end()) {
      previous = it->second;
    }
  }
  check_status(app::apply_setting(graph_, registry(), assignment));
  // --set keeps text that is not JSON as a string; here the value is always JSON.
  graph_.nodes.at(id).params[param] = converted;
  auto bad = validate_graph(graph_, registry());
  std::vector<Problem> mine;
  for (auto& p : bad) {
    if (p.node == id && p.field == param) mine.push_back(p);
  }
  if (!mine.empty()) {
    if (previous)
      graph_.nodes.at(id).params[param] = *previous;
    else
      graph_.nodes.at(id).params.erase(param);
    throw GraphFailure(mine);
  }
}

void PyGraph::link(const std::string& source, const std::string& target) {
  auto from = PortRef::parse(source);
  auto to = PortRef::parse(target);
  if (!from || !to) {
    throw Failure("link('" + source + "', '" + target +
                  "'): expected 'node.output' and 'node.input'");
  }
  node(from->node);
  const Node& reader = node(to->node);
  const NodeType& type = node_type(reader.type);
  if (type.input(to->port) == nullptr) {
    std::string names;
    for (const auto& p : type.inputs) names += (names.empty() ? "" : ", ") + p.name;
    throw Failure("node '" + to->node + "' (" + type.name + ") has no input '" + to->port +
                  "' (inputs: " + names + ")");
  }
  auto& inputs = graph_.nodes.at(to->node).inputs;
  std::optional<PortRef> previous;
  if (auto it = inputs.find(to->port); it != inputs.end()) previous = it->second;
  inputs[to->port] = *from;
  auto bad = validate_graph(graph_, registry());
  std::vector<Problem> mine;
  for (auto& p : bad) {
    if (p.node == to->node || p.message.find("cycle") != std::string::npos) mine.push_back(p);
  }
  if (!mine.empty()) {
    if (previous)
      inputs[to->port] = *previous;
    else
      inputs.erase(to->port);
    throw GraphFailure(mine);
  }
}

void PyGraph::unlink(const std::string& target) {
  auto to = PortRef::parse(target);
  if (!to) throw Failure("unlink('" + target + "'): expected 'node.input'");
  node(to->node);
  if (graph_.nodes.at(to->node).inputs.erase(to->port) == 0) {
    throw Failure("unlink('" + target + "'): input '" + to->port + "' of node '" + to->node +
                  "' is not connected");
  }
}

void PyGraph::add_node(const std::string& id, const std::string& type) {
  node_type(type);
  if (id.empty() || id.find('.') != std::string::npos) {
    throw Failure("add_node('" + id + "'): a node id is non-empty and has no '.'");
  }
  if (!graph_.nodes.emplace(id, Node{type, {}, {}}).second) {
    throw Failure("add_node('" + id + "'): the graph already has a node '" + id + "'");
  }
}

void PyGraph::remove_node(const std::string& id) {
  node(id);
  graph_.nodes.erase(id);
}

bool PyGraph::bypass(const std::string& id) const {
  return node(id).bypass;
}

void PyGraph::set_bypass(const std::string& id, bool bypass) {
  node(id);
  graph_.nodes.at(id).bypass = bypass;
}

void PyGraph::set_output(const std::string& port) {
  auto ref = PortRef::parse(port);
  if (!ref) throw Failure("output '" + port + "': expected 'node.port', e.g. 'tint.image'");
  node(ref->node);
  graph_.output = *ref;
}

void PyGraph::set_width(int width) {
  check_status(app::parse_size(std::to_string(width) + "x" + std::to_string(graph_.settings.height),
                               &graph_.settings.width, &graph_.settings.height));
}

void PyGraph::set_height(int height) {
  check_status(app::parse_size(std::to_string(graph_.settings.width) + "x" + std::to_string(height),
                               &graph_.settings.width, &graph_.settings.height));
}

void PyGraph::set_frames(std::pair<int, int> frames) {
  check_status(app::parse_frames(std::to_string(frames.first) + "-" + std::to_string(frames.second),
                                 &graph_.settings.first_frame, &graph_.settings.last_frame));
}

void PyGraph::set_precision(const std::string& precision) {
  if (precision != "half" && precision != "float") {
    throw Failure("precision must be half or float, not '" + precision + "'");
  }
  graph_.settings.precision = precision;
}

void PyGraph::set_quality(const std::string& quality) {
  if (quality != "draft" && quality != "preview" && quality != "final") {
    throw Failure("quality must be draft, preview or final, not '" + quality + "'");
  }
  graph_.settings.quality = quality;
}

}  // namespace aq::python
