// Writing graphs: canonical text (so graphs diff well in git) and atomic saves (so a crash or
// a full disk never leaves half a graph where the old one was).
//
// Canonical layout: "aquarelle" first, then "settings" (keys sorted), "nodes" (sorted by id;
// each node's keys in the order type, params, inputs; params and inputs sorted), "output",
// "editor" (kept as the editor wrote it, keys sorted). Two-space indent; arrays of plain
// values on one line; a trailing newline. Parameter values are written exactly as stored.
#include <aquarelle/core/graph_io.h>

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <random>

namespace aq {
namespace {

std::string dump_scalar(const nlohmann::json& value) {
  // Invalid UTF-8 in a string edited in memory is replaced rather than thrown about.
  return value.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace);
}

std::string string_literal(const std::string& text) {
  return dump_scalar(nlohmann::json(text));
}

bool is_flat_array(const nlohmann::json& value) {
  return value.is_array() &&
         std::none_of(value.begin(), value.end(),
                      [](const nlohmann::json& element) { return element.is_structured(); });
}

void write_value(const nlohmann::json& value, int indent, std::string* out);

void write_object_members(const nlohmann::json& object, int indent, std::string* out) {
  const std::string pad(static_cast<size_t>(indent) + 2, ' ');
  bool first = true;
  for (const auto& [key, member] : object.items()) {  // nlohmann objects iterate sorted
    *out += first ? "\n" : ",\n";
    first = false;
    *out += pad + string_literal(key) + ": ";
    write_value(member, indent + 2, out);
  }
}

void write_value(const nlohmann::json& value, int indent, std::string* out) {
  if (value.is_object()) {
    if (value.empty()) {
      *out += "{}";
      return;
    }
    *out += "{";
    write_object_members(value, indent, out);
    *out += "\n" + std::string(static_cast<size_t>(indent), ' ') + "}";
  } else if (is_flat_array(value)) {
    *out += "[";
    for (size_t i = 0; i < value.size(); ++i) {
      if (i > 0) *out += ", ";
      *out += dump_scalar(value[i]);
    }
    *out += "]";
  } else if (value.is_array()) {
    const std::string pad(static_cast<size_t>(indent) + 2, ' ');
    *out += "[";
    for (size_t i = 0; i < value.size(); ++i) {
      *out += i == 0 ? "\n" : ",\n";
      *out += pad;
      write_value(value[i], indent + 2, out);
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

void write_node(const Node& node, std::string* out) {
  const std::string pad(6, ' ');
  *out += "{\n" + pad + "\"type\": " + string_literal(node.type);
  if (!node.params.empty()) {
    nlohmann::json params = nlohmann::json::object();
    for (const auto& [name, value] : node.params) params[name] = value;
    *out += ",\n" + pad + "\"params\": ";
    write_value(params, 6, out);
  }
  if (!node.inputs.empty()) {
    nlohmann::json inputs = nlohmann::json::object();
    for (const auto& [port, source] : node.inputs) {
      if (node.inputs.count(port) == 1) {
        inputs[port] = source.str();
      } else {
        inputs[port].push_back(source.str());  // a port with several links: an array
      }
    }
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

Status save_graph_file(const Graph& graph, const std::string& path) {
  const std::string text = write_graph_text(graph);
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
