// Writing graphs: canonical text (so graphs diff well in git) and atomic saves (so a crash or
// a full disk never leaves half a graph where the old one was).
//
// Canonical layout: "aquarelle" first, then "settings" (keys sorted), "nodes" (sorted by id;
// each node's keys in the order type, bypass (only when true), params, inputs; params and inputs
// sorted), "output", "editor" (kept as the editor wrote it, keys sorted). Two-space indent; arrays
// of plain values on one line; a trailing newline. Parameter values are written exactly as stored.
//
// Saving over the text a graph was read from patches that text instead (json_text_patch.h):
// an unedited graph saves to the same bytes, an edit changes only the lines it concerns.
#include <aquarelle/core/graph_io.h>

#include "json_text_patch.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <random>
#include <set>

namespace aq {
namespace {

template <class Json>
std::string dump_scalar(const Json& value) {
  // Invalid UTF-8 in a string edited in memory is replaced rather than thrown about.
  return value.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace);
}

std::string string_literal(const std::string& text) {
  return dump_scalar(nlohmann::json(text));
}

template <class Json>
bool is_flat_array(const Json& value) {
  return value.is_array() && std::none_of(value.begin(), value.end(), [](const Json& element) {
           return element.is_structured();
         });
}

// `expand_flat_arrays`: one element per line, for files written that way (Python's json.dump).
template <class Json>
void write_value(const Json& value, int indent, std::string* out, bool expand_flat_arrays = false);

template <class Json>
void write_object_members(const Json& object, int indent, std::string* out, bool expand) {
  const std::string pad(static_cast<size_t>(indent) + 2, ' ');
  bool first = true;
  // nlohmann::json iterates its keys sorted, ordered_json in the order they were added.
  for (const auto& [key, member] : object.items()) {
    *out += first ? "\n" : ",\n";
    first = false;
    *out += pad + string_literal(key) + ": ";
    write_value(member, indent + 2, out, expand);
  }
}

template <class Json>
void write_value(const Json& value, int indent, std::string* out, bool expand_flat_arrays) {
  if (value.is_object()) {
    if (value.empty()) {
      *out += "{}";
      return;
    }
    *out += "{";
    write_object_members(value, indent, out, expand_flat_arrays);
    *out += "\n" + std::string(static_cast<size_t>(indent), ' ') + "}";
  } else if (is_flat_array(value) && !(expand_flat_arrays && !value.empty())) {
    *out += "[";
    for (size_t i = 0; i < value.size(); ++i) {
      if (i > 0) *out += ", ";
      *out += dump_scalar(value[i]);
    }
    *out += "]";
  } else if (value.is_array()) {
    if (value.empty()) {
      *out += "[]";
      return;
    }
    const std::string pad(static_cast<size_t>(indent) + 2, ' ');
    *out += "[";
    for (size_t i = 0; i < value.size(); ++i) {
      *out += i == 0 ? "\n" : ",\n";
      *out += pad;
      write_value(value[i], indent + 2, out, expand_flat_arrays);
    }
    *out += "\n" + std::string(static_cast<size_t>(indent), ' ') + "]";
  } else {
    *out += dump_scalar(value);
  }
}

// fps is a double in the model; a whole number is written without ".0" as people write it.
nlohmann::json fps_value(double fps) {
  if (std::isfinite(fps) && std::floor(fps) == fps && std::fabs(fps) < 1e15) {
    return static_cast<int64_t>(fps);
  }
  return fps;
}

nlohmann::json settings_json(const Settings& settings) {
  return nlohmann::json{
      {"width", settings.width},         {"height", settings.height},
      {"fps", fps_value(settings.fps)},  {"frames", {settings.first_frame, settings.last_frame}},
      {"precision", settings.precision}, {"quality", settings.quality}};
}

// A node's links: one source as a string, a port with several links (AQ_PORT_MULTI) as an array
// in link order.
template <class Json>
Json inputs_json(const Node& node) {
  Json inputs = Json::object();
  for (const auto& [port, source] : node.inputs) {
    if (node.inputs.count(port) == 1) {
      inputs[port] = source.str();
    } else {
      inputs[port].push_back(source.str());
    }
  }
  return inputs;
}

void write_node(const Node& node, std::string* out) {
  const std::string pad(6, ' ');
  *out += "{\n" + pad + "\"type\": " + string_literal(node.type);
  if (node.bypass) *out += ",\n" + pad + "\"bypass\": true";
  if (!node.params.empty()) {
    nlohmann::json params = nlohmann::json::object();
    for (const auto& [name, value] : node.params) params[name] = value;
    *out += ",\n" + pad + "\"params\": ";
    write_value(params, 6, out);
  }
  if (!node.inputs.empty()) {
    const auto inputs = inputs_json<nlohmann::json>(node);
    *out += ",\n" + pad + "\"inputs\": ";
    write_value(inputs, 6, out);
  }
  *out += "\n    }";
}

std::string os_reason(int error) {
  return std::strerror(error);
}

// Writes all of `text` to `fd`, retrying short writes and interruptions; errno on failure.
int write_all(int fd, const std::string& text) {
  size_t written = 0;
  while (written < text.size()) {
    const ssize_t n = ::write(fd, text.data() + written, text.size() - written);
    if (n < 0) {
      if (errno == EINTR) continue;
      return errno;
    }
    written += static_cast<size_t>(n);
  }
  return 0;
}

std::string parent_directory(const std::string& path) {
  const size_t slash = path.rfind('/');
  if (slash == std::string::npos) return ".";
  if (slash == 0) return "/";
  return path.substr(0, slash);
}

std::string random_suffix() {
  thread_local std::mt19937 generator{std::random_device{}()};
  static const char kLetters[] = "abcdefghijklmnopqrstuvwxyz0123456789";
  std::uniform_int_distribution<size_t> pick(0, sizeof(kLetters) - 2);
  std::string suffix;
  for (int i = 0; i < 6; ++i) suffix += kLetters[pick(generator)];
  return suffix;
}

// Devices, pipes and the like cannot be replaced by a rename (and must not be: saving to
// /dev/null must not delete /dev/null), so they are written in place.
Status write_in_place(const std::string& text, const std::string& path) {
  const int fd = ::open(path.c_str(), O_WRONLY | O_TRUNC | O_CLOEXEC);
  if (fd < 0) {
    return make_error("cannot save the graph to '" + path + "': " + os_reason(errno));
  }
  int error = write_all(fd, text);
  if (error == 0 && ::fsync(fd) != 0 && errno != EINVAL && errno != EROFS) error = errno;
  if (::close(fd) != 0 && error == 0) error = errno;
  if (error != 0) {
    return make_error("cannot save the graph to '" + path + "': " + os_reason(error));
  }
  return Ok{};
}

}  // namespace

std::string write_graph_text(const Graph& graph) {
  std::string out = "{\n  \"aquarelle\": " + std::to_string(graph.version) + ",\n";
  out += "  \"settings\": ";
  write_value(settings_json(graph.settings), 2, &out);
  out += ",\n  \"nodes\": {";
  bool first = true;
  for (const auto& [id, node] : graph.nodes) {
    out += first ? "\n" : ",\n";
    first = false;
    out += "    " + string_literal(id) + ": ";
    write_node(node, &out);
  }
  out += first ? "}" : "\n  }";
  if (graph.output) out += ",\n  \"output\": " + string_literal(graph.output->str());
  if (!graph.editor.is_null() && !(graph.editor.is_object() && graph.editor.empty())) {
    out += ",\n  \"editor\": ";
    write_value(graph.editor, 2, &out);
  }
  out += "\n}\n";
  return out;
}

namespace {

std::string render_new_value(const nlohmann::ordered_json& value, int indent, bool expand) {
  std::string out;
  write_value(value, indent, &out, expand);
  return out;
}

nlohmann::ordered_json ordered(const nlohmann::json& value) {
  return nlohmann::ordered_json::parse(
      value.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace));
}

// The graph as the document a file would hold, in canonical order, leaving out what the
// original file left out and the model filled with defaults (a missing "quality", an empty
// "params"), and keeping top-level members the model does not know.
nlohmann::ordered_json graph_document(const Graph& graph, const nlohmann::ordered_json& original) {
  auto had = [](const nlohmann::ordered_json& object, const char* key) {
    return object.is_object() && object.contains(key);
  };
  nlohmann::ordered_json document = nlohmann::ordered_json::object();
  document["aquarelle"] = graph.version;
  const nlohmann::json defaults = settings_json(Settings{});
  const nlohmann::json settings = settings_json(graph.settings);
  const nlohmann::ordered_json old_settings =
      had(original, "settings") ? original["settings"] : nlohmann::ordered_json::object();
  nlohmann::ordered_json written_settings = nlohmann::ordered_json::object();
  for (const char* key : {"width", "height", "fps", "frames", "precision", "quality"}) {
    if (settings[key] != defaults[key] || had(old_settings, key)) {
      written_settings[key] = ordered(settings[key]);
    }
  }
  if (!written_settings.empty() || had(original, "settings")) {
    document["settings"] = written_settings;
  }
  const nlohmann::ordered_json old_nodes =
      had(original, "nodes") ? original["nodes"] : nlohmann::ordered_json::object();
  nlohmann::ordered_json nodes = nlohmann::ordered_json::object();
  for (const auto& [id, node] : graph.nodes) {
    const nlohmann::ordered_json old_node =
        had(old_nodes, id.c_str()) ? old_nodes[id] : nlohmann::ordered_json::object();
    nlohmann::ordered_json written = nlohmann::ordered_json::object();
    written["type"] = node.type;
    if (node.bypass || had(old_node, "bypass")) written["bypass"] = node.bypass;
    if (!node.params.empty() || had(old_node, "params")) {
      nlohmann::ordered_json params = nlohmann::ordered_json::object();
      for (const auto& [name, value] : node.params) params[name] = ordered(value);
      written["params"] = params;
    }
    if (!node.inputs.empty() || had(old_node, "inputs")) {
      written["inputs"] = inputs_json<nlohmann::ordered_json>(node);
    }
    nodes[id] = written;
  }
  document["nodes"] = nodes;
  if (graph.output) document["output"] = graph.output->str();
  const bool editor_empty =
      graph.editor.is_null() || (graph.editor.is_object() && graph.editor.empty());
  if (!editor_empty || had(original, "editor")) {
    document["editor"] = editor_empty ? nlohmann::ordered_json::object() : ordered(graph.editor);
  }
  if (original.is_object()) {
    for (const auto& [key, value] : original.items()) {
      static const std::set<std::string> kModel = {"aquarelle", "settings", "nodes", "output",
                                                   "editor"};
      if (!kModel.count(key)) document[key] = value;
    }
  }
  return document;
}

}  // namespace

std::string write_graph_text(const Graph& graph, const std::string& original_text) {
  if (original_text.empty() || !nlohmann::ordered_json::accept(original_text)) {
    return write_graph_text(graph);
  }
  const auto original = nlohmann::ordered_json::parse(original_text);
  if (!original.is_object()) return write_graph_text(graph);
  auto patched = patch_json_text(original_text, graph_document(graph, original), &render_new_value);
  return patched ? *patched : write_graph_text(graph);
}

Status save_graph_file(const Graph& graph, const std::string& path) {
  return save_graph_text(write_graph_text(graph), path);
}

Status save_graph_file(const Graph& graph, const std::string& path,
                       const std::string& original_text) {
  return save_graph_text(write_graph_text(graph, original_text), path);
}

Status save_graph_text(const std::string& text, const std::string& path) {
  if (path.empty()) return make_error("cannot save the graph: no file name given");

  // Save through a symbolic link to the file it names, keeping the link.
  std::string target = path;
  struct stat info {};
  if (::lstat(path.c_str(), &info) == 0 && S_ISLNK(info.st_mode)) {
    char* resolved = ::realpath(path.c_str(), nullptr);
    if (resolved != nullptr) {
      target = resolved;
      std::free(resolved);
    }
  }
  const bool exists = ::stat(target.c_str(), &info) == 0;
  if (exists && S_ISDIR(info.st_mode)) {
    return make_error("cannot save the graph to '" + path + "': it is a directory");
  }
  if (exists && !S_ISREG(info.st_mode)) return write_in_place(text, target);

  const std::string directory = parent_directory(target);
  std::string temp;
  int fd = -1;
  for (int attempt = 0; attempt < 100 && fd < 0; ++attempt) {
    temp = target + ".tmp-" + random_suffix();
    fd = ::open(temp.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0666);
    if (fd < 0 && errno != EEXIST) break;
  }
  if (fd < 0) {
    return make_error("cannot save the graph to '" + path +
                      "': cannot create a temporary file in '" + directory +
                      "': " + os_reason(errno));
  }
  int error = 0;
  if (exists) ::fchmod(fd, info.st_mode & 07777);  // keep the old file's permissions
  error = write_all(fd, text);
  if (error == 0 && ::fsync(fd) != 0) error = errno;
  if (::close(fd) != 0 && error == 0) error = errno;
  if (error == 0 && ::rename(temp.c_str(), target.c_str()) != 0) error = errno;
  if (error != 0) {
    ::unlink(temp.c_str());
    return make_error("cannot save the graph to '" + path + "': " + os_reason(error));
  }
  // Make the rename itself durable; a failure here leaves a complete file either way.
  const int directory_fd = ::open(directory.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
  if (directory_fd >= 0) {
    ::fsync(directory_fd);
    ::close(directory_fd);
  }
  return Ok{};
}

}  // namespace aq
