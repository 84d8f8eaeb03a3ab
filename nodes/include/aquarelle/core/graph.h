// The graph model: what a version-1 graph file holds, independent of GL. The editor edits it,
// the evaluator reads it, graph_io reads, validates and writes it.
#pragma once

#include <nlohmann/json.hpp>

#include <map>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

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

// The links into a node's inputs: one per port, or several, in file order, for a port that
// takes many (AQ_PORT_MULTI, written as a JSON array of sources). Iterating visits every link
// as a (port, source) pair, so code that walks dependencies sees them all; operator[], at()
// and find() address a port's first link, which is all a plain port has.
class InputLinks : public std::multimap<std::string, PortRef> {
 public:
  using std::multimap<std::string, PortRef>::multimap;  // {{"image", PortRef{...}}, ...}
  // The port's first link, created (empty) when the port has none.
  PortRef& operator[](const std::string& port) {
    auto it = find(port);
    if (it == end()) it = emplace(port, PortRef{});
    return it->second;
  }
  const PortRef& at(const std::string& port) const {
    auto it = find(port);
    if (it == end()) throw std::out_of_range("input '" + port + "' is not connected");
    return it->second;
  }
  // Appends a link after the port's others.
  void add(const std::string& port, PortRef source) { emplace(port, std::move(source)); }
  // Every link of the port, in order.
  std::vector<PortRef> links(const std::string& port) const {
    std::vector<PortRef> out;
    auto [first, last] = equal_range(port);
    for (auto it = first; it != last; ++it) out.push_back(it->second);
    return out;
  }
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
  InputLinks inputs;  // input port -> source output(s)
  // "bypass": true in the file: the node passes its input through (Nuke's disable), for the
  // render as for the editor; see bypass.h.
  bool bypass = false;
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
