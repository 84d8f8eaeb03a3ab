// The graph model: what a version-1 graph file holds, independent of GL. The editor edits it,
// the evaluator reads it, graph_io reads, validates and writes it.
#pragma once

#include <nlohmann/json.hpp>

#include <map>
#include <optional>
#include <string>

namespace aq {

// A reference to an output port, written "<node id>.<port>" in files.
struct PortRef {
  std::string node;
  std::string port;
  std::string str() const { return node + "." + port; }
  bool operator==(const PortRef&) const = default;
  // Splits at the last '.'; nullopt when there is no '.', or either side is empty.
  static std::optional<PortRef> parse(const std::string& text);
};

struct Settings {
  int width = 1280;
  int height = 720;
  double fps = 24.0;
  int first_frame = 1;
  int last_frame = 1;
  std::string precision = "half";  // "half" | "float"
  std::string quality = "final";   // "draft" | "preview" | "final"
};

struct Node {
  std::string type;
  // Parameter values as written (JSON); missing parameters take their defaults.
  std::map<std::string, nlohmann::json> params;
  std::map<std::string, PortRef> inputs;  // input port -> source output
};

struct Graph {
  int version = 1;
  Settings settings;
  std::map<std::string, Node> nodes;  // keyed by node id
  std::optional<PortRef> output;
  nlohmann::json editor = nlohmann::json::object();  // the editor's alone; kept verbatim
  std::string source_path;  // the file it came from (for relative paths), may be empty
};

}  // namespace aq
