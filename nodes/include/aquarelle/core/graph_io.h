// Reading, validating and writing version-1 graph files (see DESIGN.md, "Graph file format").
//
// Reading reports every problem at once, each with the node id, the port or parameter, and
// the place in the file (line and column, and the JSON pointer). Writing is canonical (stable
// key order, one node per block) and atomic (temporary file, flush, rename).
#pragma once

#include <aquarelle/core/graph.h>
#include <aquarelle/core/registry.h>
#include <aquarelle/core/result.h>

#include <string>
#include <vector>

namespace aq {

struct Problem {
  std::string file;     // may be empty for text not read from a file
  int line = 0;         // 1-based; 0 when unknown
  int column = 0;       // 1-based; 0 when unknown
  std::string pointer;  // JSON pointer, e.g. "/nodes/blur/params/sigma"
  std::string node;     // node id, when the problem belongs to a node
  std::string field;    // port or parameter name, or a settings key
  std::string message;  // what is wrong and how to fix it
};

// "graph.json:12:7: node 'blur', parameter 'sigma': expected a number, got a string"
std::string format_problem(const Problem& problem);
std::string format_problems(const std::vector<Problem>& problems);

struct ReadResult {
  Graph graph;
  std::vector<Problem> problems;  // empty when the graph is valid
  bool ok() const { return problems.empty(); }
};

// Parses and validates. `file` names the source in messages and becomes graph.source_path.
ReadResult read_graph_text(const std::string& text, const Registry& registry,
                           const std::string& file = "");
ReadResult read_graph_file(const std::string& path, const Registry& registry);

// Validates a graph model (e.g. after editing); locations are JSON pointers only.
std::vector<Problem> validate_graph(const Graph& graph, const Registry& registry);

// Frame numbers lie in -kMaxFrameNumber..kMaxFrameNumber and a range holds at most
// kMaxFrameCount frames: a range at the top of `int` would wrap around and write files
// forever. The settings' frames (validate_graph), --frames and the renderer all check it.
inline constexpr int kMaxFrameNumber = 9'999'999;
inline constexpr int kMaxFrameCount = 1'000'000;
// Empty when [first, last] is a usable range; else why not (one line).
std::string frame_range_problem(long long first, long long last);

// An output depends on at most kMaxGraphNodes nodes: every one is real work each frame (a
// chain of 20,000 `erode` nodes ran for 151 s at 16x16, 1,000 for 4 s). validate_graph and the
// planner (so every entry point: render, bench, the editor, the Python module) refuse more.
inline constexpr size_t kMaxGraphNodes = 1000;
// A graph file holds at most kMaxGraphFileNodes nodes, used or not: 400,000 unconnected nodes
// in 11 MB took 10 s and 720 MB to read (about 1.8 KB a node) and printed a problem for each.
inline constexpr size_t kMaxGraphFileNodes = 100'000;
// Empty when the nodes `output` depends on (itself included) are at most kMaxGraphNodes; else
// why not (one line). Nodes the output does not read are not counted.
std::string node_count_problem(const Graph& graph, const PortRef& output);

// Canonical JSON text: keys sorted, one node per block, two-space indent, trailing newline.
std::string write_graph_text(const Graph& graph);
// The text the graph was read from, patched to hold `graph`: members that did not change keep
// their bytes (order, layout, number text), removed ones go, new ones are appended in the
// file's style. Unedited: the same bytes. Falls back to the canonical text when `original_text`
// is empty or not JSON.
std::string write_graph_text(const Graph& graph, const std::string& original_text);
// Atomic: writes PATH.tmp-XXXX next to it, flushes, fsyncs, renames over PATH.
Status save_graph_file(const Graph& graph, const std::string& path);
// Same, writing write_graph_text(graph, original_text).
Status save_graph_file(const Graph& graph, const std::string& path,
                       const std::string& original_text);
// The atomic write of any graph text.
Status save_graph_text(const std::string& text, const std::string& path);

// What `aquarelle validate` finds in the files a valid graph names: a path parameter that is
// missing, not a regular file or unreadable, a `read` image that is not an image, and what
// node types that check their files report (aq_node_desc::check: a file that is not a mesh,
// a missing texture or material file). Errors: the graph will not render; warnings: it
// renders with a stand-in the message names. Located in graph.source_path when set.
struct FileProblems {
  std::vector<Problem> errors;
  std::vector<Problem> warnings;
};
FileProblems check_graph_files(const Graph& graph, const Registry& registry);

// Resolved value of a parameter: the graph's value or the type's default, as JSON.
nlohmann::json param_value_or_default(const Node& node, const ParamInfo& param);

}  // namespace aq
