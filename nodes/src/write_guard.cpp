// The shared "may this path be written" check (see write_guard.h).
#include <aquarelle/core/color.h>
#include <aquarelle/core/graph_io.h>
#include <aquarelle/core/write_guard.h>
#include <sys/stat.h>
#include <aquarelle/sdk/regular_file.hpp>

#include <filesystem>
#include <nlohmann/json.hpp>
#include <sstream>

#include <aquarelle/core/message_text.h>

namespace aq {

namespace fs = std::filesystem;

namespace {

// Scanning what a mesh names reads at most this much of it: the names come first in practice,
// and the scan must never be the slow part or read a huge file whole.
constexpr uint64_t kScanBytes = 16ull << 20;

std::string read_head(const std::string& path) {
  std::string text, why;
  if (files::regular_file_size(path) > kScanBytes) return "";
  if (!files::read_regular_file(path, kScanBytes, &text, &why)) return "";
  return text;
}

std::string trim(const std::string& text) {
  const auto begin = text.find_first_not_of(" \t\r");
  if (begin == std::string::npos) return "";
  const auto end = text.find_last_not_of(" \t\r");
  return text.substr(begin, end - begin + 1);
}

// The textures of an MTL file: the rest of each map_*/bump/disp/norm/refl line, and its last
// word (options such as `-bm 1.0` come before the name).
void add_mtl_textures(const fs::path& mtl, std::vector<ReadFile>* out) {
  std::istringstream lines(read_head(mtl.string()));
  const std::string role = "a texture named by " + mtl.string();
  for (std::string line; std::getline(lines, line);) {
    std::istringstream words(line);
    std::string keyword;
    words >> keyword;
    if (!(keyword.rfind("map_", 0) == 0 || keyword == "bump" || keyword == "disp" ||
          keyword == "norm" || keyword == "refl" || keyword == "decal")) {
      continue;
    }
    std::string rest;
    std::getline(words, rest);
    rest = trim(rest);
    if (rest.empty()) continue;
    const auto last_space = rest.find_last_of(" \t");
    for (const std::string& name :
         {rest, last_space == std::string::npos ? rest : rest.substr(last_space + 1)}) {
      out->push_back({(mtl.parent_path() / name).lexically_normal().string(), role});
    }
  }
}

void add_obj_references(const fs::path& obj, std::vector<ReadFile>* out) {
  std::istringstream lines(read_head(obj.string()));
  for (std::string line; std::getline(lines, line);) {
    std::istringstream words(line);
    std::string keyword;
    words >> keyword;
    if (keyword != "mtllib") continue;
    std::string rest;
    std::getline(words, rest);
    rest = trim(rest);
    std::vector<std::string> names{rest};
    std::istringstream each(rest);
    for (std::string name; each >> name;) names.push_back(name);
    for (const auto& name : names) {
      const fs::path mtl = (obj.parent_path() / name).lexically_normal();
      out->push_back({mtl.string(), "a material file named by " + obj.string()});
      add_mtl_textures(mtl, out);
    }
  }
}

void add_gltf_references(const fs::path& gltf, std::vector<ReadFile>* out) {
  const auto json = nlohmann::json::parse(read_head(gltf.string()), nullptr, false);
  if (!json.is_object()) return;
  for (const char* list : {"buffers", "images"}) {
    const auto it = json.find(list);
    if (it == json.end() || !it->is_array()) continue;
    for (const auto& item : *it) {
      if (!item.is_object() || !item.contains("uri") || !item["uri"].is_string()) continue;
      const std::string uri = item["uri"].get<std::string>();
      if (uri.rfind("data:", 0) == 0) continue;
      out->push_back({(gltf.parent_path() / uri).lexically_normal().string(),
                      std::string("a file named by ") + gltf.string()});
    }
  }
}

// What a mesh or material file names in turn.
void add_references(const fs::path& path, std::vector<ReadFile>* out) {
  std::string extension = path.extension().string();
  for (char& c : extension) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  if (extension == ".obj") add_obj_references(path, out);
  if (extension == ".mtl") add_mtl_textures(path, out);
  if (extension == ".gltf") add_gltf_references(path, out);
}

bool same_file(const std::string& a, const std::string& b) {
  std::error_code ec;
  if (fs::equivalent(a, b, ec) && !ec) return true;  // links, hard links, other spellings
  const auto ca = fs::weakly_canonical(a, ec);
  if (ec) return false;
  const auto cb = fs::weakly_canonical(b, ec);
  return !ec && ca == cb;
}

}  // namespace

std::vector<ReadFile> files_read_by(const Graph& graph, const Registry& registry,
                                    const ColorConfig* color) {
  const fs::path graph_dir =
      graph.source_path.empty() ? fs::path() : fs::path(graph.source_path).parent_path();
  std::vector<ReadFile> files;
  if (!graph.source_path.empty()) files.push_back({graph.source_path, "the graph file"});
  for (const auto& [id, node] : graph.nodes) {
    const NodeType* type = registry.find(node.type);
    if (type == nullptr) continue;
    for (const ParamInfo& info : type->params) {
      if (info.type != AQ_PARAM_PATH) continue;
      const nlohmann::json value = param_value_or_default(node, info);
      if (!value.is_string() || value.get<std::string>().empty()) continue;
      fs::path path = value.get<std::string>();
      if (path.is_relative() && !graph_dir.empty()) path = graph_dir / path;
      path = path.lexically_normal();
      files.push_back({path.string(), "the input file"});
      add_references(path, &files);
    }
  }
  if (color != nullptr) {
    for (const auto& file : color->files()) files.push_back({file, "an OpenColorIO file"});
  }
  return files;
}

Status check_may_write(const std::string& option, const std::string& path) {
  struct stat info {};
  if (::stat(path.c_str(), &info) == 0 && !S_ISREG(info.st_mode)) {
    return make_error(option + " " + quote_for_message(path) + " is " +
                      files::kind_of(info.st_mode) +
                      "; only regular files are written: choose another output path");
  }
  if (path.find('\0') != std::string::npos) {
    return make_error(option + ": the path contains a NUL character");
  }
  return Ok{};
}

Status check_may_write(const std::string& option, const std::string& path,
                       const std::vector<ReadFile>& reads) {
  if (auto s = check_may_write(option, path); !s.ok()) return s;
  for (const auto& read : reads) {
    if (!same_file(path, read.path)) continue;
    if (read.role == "the graph file") {
      return make_error(option + " " + quote_for_message(path) + " is the graph file " +
                        quote_for_message(read.path) +
                        "; writing it would destroy the graph: choose another output path");
    }
    return make_error(option + " " + quote_for_message(path) + " is the input file " +
                      quote_for_message(read.path) + " (" + escape_for_message(read.role) +
                      ") that the graph reads; writing it would destroy the input: choose "
                      "another output path");
  }
  return Ok{};
}

}  // namespace aq
