// Reading a version-1 graph file into the model:
//
//   text ─► nesting depth check (no recursion) ─► nlohmann parse (syntax errors -> line:col)
//        ─► locator scan (pointer -> line:col, duplicate keys)
//        ─► structure: keys, JSON types of settings/nodes/inputs/output ─► Graph
//        ─► graph_checks::check_graph (types, ports, params, cycles, output)
//        ─► every problem gets its line and column from the locator, sorted by place.
//
// Nothing throws out of here: every failure becomes a Problem.
#include <aquarelle/core/graph_io.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <limits>
#include <tuple>

#include <aquarelle/sdk/regular_file.hpp>

#include "graph_checks.h"
#include "json_locator.h"

namespace aq {
namespace {

using graph_checks::problem_at;
using graph_checks::quoted;
using json_text::JsonLocator;
using json_text::TextPosition;

// Far deeper than any graph file needs, far shallower than what would exhaust the stack of
// code that walks JSON recursively.
constexpr int kMaxNesting = 64;

// Graph files are a few kilobytes; far larger is not a graph.
constexpr uint64_t kMaxGraphFileBytes = 64ull << 20;

// nlohmann's what() starts with "[json.exception.parse_error.101] parse error at line 2,
// column 6: "; the place is reported separately, so keep only the explanation.
std::string parse_error_explanation(const std::string& what) {
  const size_t column = what.find("column ");
  const size_t colon = what.find(": ", column == std::string::npos ? 0 : column);
  if (colon == std::string::npos) return what;
  return what.substr(colon + 2);
}

class GraphReader {
 public:
  GraphReader(const std::string& text, const Registry& registry, const std::string& file)
      : text_(text), registry_(registry), file_(file) {}

  ReadResult read() {
    result_.graph.source_path = file_;
    if (parse()) read_root();
    for (Problem& problem : result_.problems) {
      problem.file = file_;
      if (problem.line == 0) {
        const TextPosition position = locator_.position(problem.pointer);
        problem.line = position.line;
        problem.column = position.column;
      }
    }
    std::stable_sort(result_.problems.begin(), result_.problems.end(),
                     [](const Problem& a, const Problem& b) {
                       return std::tie(a.line, a.column) < std::tie(b.line, b.column);
                     });
    return std::move(result_);
  }

 private:
  void add(const std::string& pointer, std::string message) {
    result_.problems.push_back(problem_at(pointer, std::move(message)));
  }
  void add_at(TextPosition position, std::string message) {
    Problem problem;
    problem.line = position.line;
    problem.column = position.column;
    problem.message = std::move(message);
    result_.problems.push_back(std::move(problem));
  }

  // Fills root_ and locator_; false when the text is not JSON that can be read further.
  bool parse() {
    const size_t too_deep = json_text::find_nesting_deeper_than(text_, kMaxNesting);
    if (too_deep != std::string::npos) {
      add_at(json_text::position_of_offset(text_, too_deep),
             "arrays and objects nest deeper than " + std::to_string(kMaxNesting) +
                 " levels; a graph file never needs that, so it is not read");
      return false;
    }
    try {
      root_ = nlohmann::json::parse(text_);
    } catch (const nlohmann::json::parse_error& error) {
      const size_t offset = error.byte > 0 ? error.byte - 1 : 0;
      add_at(json_text::position_of_offset(text_, offset),
             "malformed JSON: " + parse_error_explanation(error.what()));
      return false;
    } catch (const nlohmann::json::exception& error) {
      // Numbers too large for a double are refused without a position: find it ourselves.
      const JsonLocator locator = JsonLocator::scan(text_, kMaxNesting);
      if (locator.has_overflowing_number()) {
        add_at(locator.overflowing_number_position(),
               "number " + locator.overflowing_number() + " is too large to represent");
      } else {
        add_at(TextPosition{}, std::string("malformed JSON: ") + error.what());
      }
      return false;
    }
    locator_ = JsonLocator::scan(text_, kMaxNesting);
    for (const json_text::DuplicateKey& duplicate : locator_.duplicates()) {
      const std::vector<std::string> segments = json_text::split_pointer(duplicate.pointer);
      Problem problem =
          problem_at(duplicate.pointer, "key " + quoted(segments.empty() ? "" : segments.back()) +
                                            " appears twice (first at line " +
                                            std::to_string(duplicate.first.line) + ", column " +
                                            std::to_string(duplicate.first.column) +
                                            "); only the last would be used: remove one");
      problem.line = duplicate.second.line;
      problem.column = duplicate.second.column;
      result_.problems.push_back(std::move(problem));
    }
    return true;
  }

  void read_root() {
    if (!root_.is_object()) {
      add("", "a graph file holds a JSON object ({\"aquarelle\": 1, ...}), not " +
                  graph_checks::json_kind(root_));
      return;
    }
    for (const auto& [key, value] : root_.items()) {
      static const char* kKnown[] = {"aquarelle", "settings", "nodes", "output", "editor"};
      if (std::find(std::begin(kKnown), std::end(kKnown), key) == std::end(kKnown)) {
        add("/" + json_text::escape_pointer_segment(key),
            "unknown key " + quoted(key) +
                "; a graph file holds aquarelle, settings, nodes, output and editor");
      }
    }
    if (!read_version()) return;  // another version's layout would only give noise
    if (root_.contains("settings")) read_settings(root_["settings"]);
    if (root_.contains("nodes")) {
      if (!read_nodes(root_["nodes"])) return;  // too many to say more about
    } else {
      add("/nodes", "no \"nodes\": a graph needs at least the node that gives its output");
    }
    if (root_.contains("output")) read_output(root_["output"]);
    if (root_.contains("editor")) {
      if (root_["editor"].is_object()) {
        result_.graph.editor = root_["editor"];
        migrate_editor_bypass();
      } else {
        add("/editor",
            "\"editor\" must be an object, not " + graph_checks::json_kind(root_["editor"]));
      }
    }
    auto checks = graph_checks::check_graph(result_.graph, registry_, already_);
    result_.problems.insert(result_.problems.end(), std::make_move_iterator(checks.begin()),
                            std::make_move_iterator(checks.end()));
  }

  // Graphs saved by editors before bypass moved onto the node kept it in
  // editor.bypassed[id] = true; such a node is bypassed, and the mark moves onto it (the next
  // save writes "bypass": true on the node).
  void migrate_editor_bypass() {
    nlohmann::json& editor = result_.graph.editor;
    auto marks = editor.find("bypassed");
    if (marks == editor.end()) return;
    if (marks->is_object()) {
      for (const auto& [id, mark] : marks->items()) {
        auto node = result_.graph.nodes.find(id);
        if (node != result_.graph.nodes.end() && mark.is_boolean() && mark.get<bool>()) {
          node->second.bypass = true;
        }
      }
    }
    editor.erase(marks);
  }

  bool read_version() {
    if (!root_.contains("aquarelle")) {
      add("", "no \"aquarelle\" key: a graph file starts with {\"aquarelle\": 1, ...}");
      return true;
    }
    const nlohmann::json& version = root_["aquarelle"];
    if (version.is_number_integer() && version.get<int64_t>() == 1) return true;
    add("/aquarelle", "unsupported version " +
                          version.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace) +
                          "; this build reads version 1 (\"aquarelle\": 1)");
    return false;
  }

  // An integer that fits an int, or nullopt after reporting why not.
  std::optional<int> read_int(const std::string& pointer, const nlohmann::json& value,
                              const std::string& what) {
    if (!value.is_number_integer()) {
      add(pointer, what + " must be an integer, not " + graph_checks::json_kind(value));
      return std::nullopt;
    }
    if (value.is_number_unsigned() &&
        value.get<uint64_t>() > static_cast<uint64_t>(std::numeric_limits<int>::max())) {
      add(pointer, what + " " + value.dump() + " is too large");
      return std::nullopt;
    }
    const int64_t number = value.get<int64_t>();
    if (number < std::numeric_limits<int>::min() || number > std::numeric_limits<int>::max()) {
      add(pointer, what + " " + value.dump() + " is out of range");
      return std::nullopt;
    }
    return static_cast<int>(number);
  }

  void read_settings(const nlohmann::json& settings) {
    if (!settings.is_object()) {
      add("/settings", "\"settings\" must be an object, not " + graph_checks::json_kind(settings));
      return;
    }
    Settings& out = result_.graph.settings;
    for (const auto& [key, value] : settings.items()) {
      const std::string pointer = "/settings/" + json_text::escape_pointer_segment(key);
      if (key == "width" || key == "height") {
        if (auto number = read_int(pointer, value, key)) {
          (key == "width" ? out.width : out.height) = *number;
        }
      } else if (key == "fps") {
        if (value.is_number()) {
          out.fps = value.get<double>();
        } else {
          add(pointer, "fps must be a number, not " + graph_checks::json_kind(value));
        }
      } else if (key == "frames") {
        if (!value.is_array() || value.size() != 2) {
          add(pointer, "frames must be [first, last], e.g. [1, 48]");
          continue;
        }
        auto first = read_int(pointer + "/0", value[0], "first frame");
        auto last = read_int(pointer + "/1", value[1], "last frame");
        if (first && last) {
          out.first_frame = *first;
          out.last_frame = *last;
        }
      } else if (key == "precision" || key == "quality") {
        if (value.is_string()) {
          (key == "precision" ? out.precision : out.quality) = value.get<std::string>();
        } else {
          add(pointer, key + " must be a string, not " + graph_checks::json_kind(value));
        }
      } else {
        add(pointer, "unknown setting " + quoted(key) +
                         "; settings are width, height, fps, frames, precision and quality");
      }
    }
  }

  // False when the graph has more nodes than a file may hold (nothing else is read).
  bool read_nodes(const nlohmann::json& nodes) {
    if (!nodes.is_object()) {
      add("/nodes",
          "\"nodes\" must be an object keyed by node id, not " + graph_checks::json_kind(nodes));
      return true;
    }
    if (nodes.size() > kMaxGraphFileNodes) {
      add("/nodes", "the graph holds " + std::to_string(nodes.size()) + " nodes, more than the " +
                        std::to_string(kMaxGraphFileNodes) +
                        " a graph file may hold: remove the nodes its output does not use or "
                        "split it into several graphs");
      return false;
    }
    for (const auto& [id, value] : nodes.items()) read_node(id, value);
    return true;
  }

  void read_node(const std::string& id, const nlohmann::json& value) {
    const std::string pointer = graph_checks::node_pointer(id);
    Node& node = result_.graph.nodes[id];
    if (!value.is_object()) {
      add(pointer,
          "a node must be an object {\"type\": ..., \"params\": ..., \"inputs\": ...}, "
          "not " +
              graph_checks::json_kind(value));
      already_.node_types.insert(id);
      return;
    }
    for (const auto& [key, member] : value.items()) {
      if (key != "type" && key != "params" && key != "inputs" && key != "bypass") {
        add(pointer + "/" + json_text::escape_pointer_segment(key),
            "unknown key " + quoted(key) +
                " in a node; a node holds type, params, inputs and bypass");
      }
    }
    if (!value.contains("type")) {
      add(pointer, "node " + quoted(id) + " has no \"type\"");
      already_.node_types.insert(id);
    } else if (!value["type"].is_string()) {
      add(pointer + "/type",
          "\"type\" must be a string, not " + graph_checks::json_kind(value["type"]));
      already_.node_types.insert(id);
    } else {
      node.type = value["type"].get<std::string>();
    }
    if (value.contains("params")) {
      const nlohmann::json& params = value["params"];
      if (params.is_object()) {
        for (const auto& [name, param] : params.items()) node.params[name] = param;
      } else {
        add(pointer + "/params",
            "\"params\" must be an object, not " + graph_checks::json_kind(params));
      }
    }
    if (value.contains("inputs")) read_inputs(id, value["inputs"], &node);
    if (value.contains("bypass")) {
      if (value["bypass"].is_boolean()) {
        node.bypass = value["bypass"].get<bool>();
      } else {
        add(pointer + "/bypass",
            "\"bypass\" must be true or false, not " + graph_checks::json_kind(value["bypass"]));
      }
    }
  }

  void read_inputs(const std::string& id, const nlohmann::json& inputs, Node* node) {
    if (!inputs.is_object()) {
      add(graph_checks::node_pointer(id) + "/inputs",
          "\"inputs\" must be an object, not " + graph_checks::json_kind(inputs));
      return;
    }
    for (const auto& [port, value] : inputs.items()) {
      // A port that takes several links lists its sources in an array (validation checks the
      // port allows it).
      const bool many = value.is_array();
      const nlohmann::json sources = many ? value : nlohmann::json::array({value});
      for (size_t k = 0; k < sources.size(); ++k) {
        const nlohmann::json& source = sources[k];
        const std::string pointer = graph_checks::input_pointer(id, port) +
                                    (many ? "/" + std::to_string(k) : std::string());
        std::optional<PortRef> ref =
            source.is_string() ? PortRef::parse(source.get<std::string>()) : std::nullopt;
        if (!ref) {
          const std::string shown = source.is_string() ? quoted(source.get<std::string>())
                                                       : graph_checks::json_kind(source);
          add(pointer, "source " + shown + " must be a string \"<node id>.<output port>\"" +
                           (many ? "" : " (or an array of them for a port taking many links)"));
          already_.inputs.insert({id, port});
          continue;
        }
        node->inputs.add(port, *ref);
      }
    }
  }

  void read_output(const nlohmann::json& output) {
    std::optional<PortRef> ref =
        output.is_string() ? PortRef::parse(output.get<std::string>()) : std::nullopt;
    if (!ref) {
      const std::string shown =
          output.is_string() ? quoted(output.get<std::string>()) : graph_checks::json_kind(output);
      add("/output", "output " + shown + " must be a string \"<node id>.<output port>\"");
      already_.output = true;
      return;
    }
    result_.graph.output = *ref;
  }

  const std::string& text_;
  const Registry& registry_;
  const std::string& file_;
  nlohmann::json root_;
  JsonLocator locator_;
  graph_checks::AlreadyReported already_;
  ReadResult result_;
};

}  // namespace

ReadResult read_graph_text(const std::string& text, const Registry& registry,
                           const std::string& file) {
  return GraphReader(text, registry, file).read();
}

ReadResult read_graph_file(const std::string& path, const Registry& registry) {
  auto unreadable = [&](const std::string& why) {
    ReadResult result;
    result.graph.source_path = path;
    Problem problem;
    problem.file = path;
    problem.message = "cannot read the graph file: " + why;
    result.problems.push_back(std::move(problem));
    return result;
  };
  // Only a regular file: a FIFO or /dev/zero would block or grow without end.
  std::string text, why;
  if (!files::read_regular_file(path, kMaxGraphFileBytes, &text, &why)) {
    return unreadable(why == "no such file" ? std::strerror(ENOENT) : why);
  }
  return read_graph_text(text, registry, path);
}

}  // namespace aq
