// `aquarelle validate`'s look at the files a graph names, after the graph itself is valid:
//
//   every non-empty path parameter ─► resolved against the graph file's folder (as the
//   evaluator does) ─► missing, not a regular file, unreadable: an error
//   built-in `read` ─► OpenImageIO opens the header: not an image is an error
//   plugin node types with aq_node_desc::check ─► the plugin says what is wrong inside its
//   files (a file that is not a mesh is an error; a missing texture or MTL file a warning)
//
// Errors mean the graph will not render (render exits 1 for the same files); warnings mean it
// renders with a stand-in the message names. Every problem names the node, the parameter and
// the resolved path, and is located in the file like reading's problems.
#include <aquarelle/core/graph_io.h>
#include <aquarelle/core/image_io.h>

#include <unistd.h>
#include <cstddef>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <system_error>

#include "graph_checks.h"
#include "json_locator.h"

namespace aq {

namespace {

namespace fs = std::filesystem;
using graph_checks::param_pointer;
using graph_checks::problem_at;

std::string resolved_path(const Graph& graph, const std::string& path) {
  const fs::path graph_dir = fs::path(graph.source_path).parent_path();
  if (fs::path(path).is_relative() && !graph_dir.empty()) {
    return (graph_dir / path).lexically_normal().string();
  }
  return path;
}

// Why `path` cannot be read as a file, or "".
std::string unreadable_reason(const std::string& path) {
  std::error_code error;
  const fs::file_status status = fs::status(path, error);
  if (!fs::exists(status)) return "does not exist";
  if (fs::is_directory(status)) return "is a directory, not a file";
  if (!fs::is_regular_file(status)) return "is not a regular file";
  if (::access(path.c_str(), R_OK) != 0) return "cannot be read (permissions)";
  return "";
}

// The parameter values a plugin's process() would get (defaults filled in, paths resolved).
struct ResolvedParams {
  std::vector<aq_param_value> values;
  std::vector<std::string> strings;
};

ResolvedParams resolve_params(const Graph& graph, const Node& node, const NodeType& type) {
  ResolvedParams out;
  out.values.assign(type.params.size(), aq_param_value{{0, 0, 0}, 0, nullptr});
  out.strings.resize(type.params.size());
  for (size_t p = 0; p < type.params.size(); ++p) {
    const ParamInfo& info = type.params[p];
    const nlohmann::json value = param_value_or_default(node, info);
    aq_param_value& v = out.values[p];
    switch (info.type) {
      case AQ_PARAM_FLOAT:
      case AQ_PARAM_INT:
        v.f[0] = value.is_number() ? value.get<double>() : info.default_value[0];
        v.i = static_cast<int64_t>(v.f[0]);
        break;
      case AQ_PARAM_BOOL:
        v.i = value.is_boolean() ? value.get<bool>() : info.default_value[0] != 0;
        break;
      case AQ_PARAM_ENUM:
        v.i = static_cast<int64_t>(info.default_value[0]);
        for (size_t e = 0; e < info.enum_values.size(); ++e) {
          if (value.is_string() && info.enum_values[e] == value.get<std::string>()) {
            v.i = static_cast<int64_t>(e);
          }
        }
        break;
      case AQ_PARAM_COLOR:
      case AQ_PARAM_VEC3:
        for (int c = 0; c < 3; ++c) {
          v.f[c] = value.is_array() && value.size() == 3 && value[c].is_number()
                       ? value[c].get<double>()
                       : info.default_value[c];
        }
        break;
      case AQ_PARAM_STRING:
      case AQ_PARAM_PATH:
        out.strings[p] = value.is_string() ? value.get<std::string>() : info.default_string;
        if (info.type == AQ_PARAM_PATH && !out.strings[p].empty()) {
          out.strings[p] = resolved_path(graph, out.strings[p]);
        }
        break;
    }
  }
  for (size_t p = 0; p < type.params.size(); ++p) out.values[p].s = out.strings[p].c_str();
  return out;
}

struct CheckSink {
  const std::string* node_id;
  const NodeType* type;
  FileProblems* out;
};

void report_from_plugin(void* data, int level, uint32_t param, const char* message) {
  auto* sink = static_cast<CheckSink*>(data);
  const std::string name =
      param < sink->type->params.size() ? sink->type->params[param].name : std::string();
  Problem problem = problem_at(name.empty() ? graph_checks::node_pointer(*sink->node_id)
                                            : param_pointer(*sink->node_id, name),
                               message != nullptr ? message : "(no message)");
  (level == 0 ? sink->out->errors : sink->out->warnings).push_back(std::move(problem));
}

void locate(const Graph& graph, FileProblems* problems) {
  std::ifstream in(graph.source_path, std::ios::binary);
  const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const json_text::JsonLocator locator = json_text::JsonLocator::scan(text, 256);
  for (auto* list : {&problems->errors, &problems->warnings}) {
    for (Problem& problem : *list) {
      problem.file = graph.source_path;
      const json_text::TextPosition position = locator.position(problem.pointer);
      problem.line = position.line;
      problem.column = position.column;
    }
  }
}

}  // namespace

FileProblems check_graph_files(const Graph& graph, const Registry& registry) {
  FileProblems out;
  for (const auto& [id, node] : graph.nodes) {
    const NodeType* type = registry.find(node.type);
    if (type == nullptr) continue;
    const ResolvedParams params = resolve_params(graph, node, *type);
    bool files_readable = true;
    for (size_t p = 0; p < type->params.size(); ++p) {
      if (type->params[p].type != AQ_PARAM_PATH || params.strings[p].empty()) continue;
      const std::string& path = params.strings[p];
      if (std::string why = unreadable_reason(path); !why.empty()) {
        out.errors.push_back(problem_at(param_pointer(id, type->params[p].name),
                                        "'" + path + "' " + why +
                                            "; fix the path (relative "
                                            "paths start at the graph file's folder)"));
        files_readable = false;
        continue;
      }
      if (type->desc == nullptr && type->name == "read") {
        static Result<ColorConfig> config = ColorConfig::load();
        if (!config.ok()) continue;
        if (auto colorspace = file_colorspace(path, *config); !colorspace.ok()) {
          out.errors.push_back(problem_at(
              param_pointer(id, type->params[p].name),
              "'" + path + "' is not an image OpenImageIO reads: " + colorspace.message()));
          files_readable = false;
        }
      }
    }
    const aq_node_desc* desc = type->desc;
    if (!files_readable || desc == nullptr ||
        desc->struct_size < offsetof(aq_node_desc, check) + sizeof(desc->check) ||
        desc->check == nullptr) {
      continue;
    }
    CheckSink sink{&id, type, &out};
    desc->check(params.values.data(), static_cast<uint32_t>(params.values.size()),
                &report_from_plugin, &sink);
  }
  if (!graph.source_path.empty()) locate(graph, &out);
  return out;
}

}  // namespace aq
