// Bad graph files, systematically: every value of the repository's graphs replaced by every
// other JSON kind, every prefix of a graph file, deep nesting of objects, link sources of
// odd shapes, and graphs of 10,000 nodes that are wide or all wrong. The reader must return
// problems (never crash, throw or hang) and every problem must say where it is. The hand-
// written cases with exact messages and places are in graph_io_test.cpp; findings of the
// fuzzer (tests/fuzz, scripts/fuzz.sh) become regression cases at the end of this file.
#include <aquarelle/core/graph_io.h>
#include <aquarelle/core/plugin_loader.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <functional>

#include "support/harness.h"

namespace {

namespace fs = std::filesystem;
using nlohmann::json;

const aq::Registry& registry() {
  return aq::test::registry();
}

std::string file_text(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), {});
}

std::vector<std::string> repository_graphs() {
  std::vector<std::string> paths;
  for (const auto& entry : fs::directory_iterator(aq::test::source_path("graphs"))) {
    if (entry.path().extension() == ".json") paths.push_back(entry.path().string());
  }
  std::sort(paths.begin(), paths.end());
  return paths;
}

// Every problem says what is wrong and where: a JSON pointer or a line.
void expect_located(const aq::ReadResult& result, const std::string& what) {
  for (const aq::Problem& problem : result.problems) {
    EXPECT_FALSE(problem.message.empty()) << what;
    EXPECT_TRUE(problem.line > 0 || !problem.pointer.empty())
        << what << ": " << aq::format_problem(problem);
  }
}

// Calls `visit` with the JSON pointer of every value below `value` (not the root).
void for_each_pointer(const json& value, const std::string& pointer,
                      const std::function<void(const std::string&)>& visit) {
  if (!pointer.empty()) visit(pointer);
  if (value.is_object()) {
    for (const auto& [key, child] : value.items()) {
      std::string escaped;
      for (char c : key) escaped += c == '~' ? "~0" : c == '/' ? "~1" : std::string(1, c);
      for_each_pointer(child, pointer + "/" + escaped, visit);
    }
  } else if (value.is_array()) {
    for (size_t i = 0; i < value.size(); ++i) {
      for_each_pointer(value[i], pointer + "/" + std::to_string(i), visit);
    }
  }
}

TEST(BadGraph, RepositoryGraphsAreValidToStartFrom) {
  for (const std::string& path : repository_graphs()) {
    const aq::ReadResult result = aq::read_graph_file(path, registry());
    EXPECT_TRUE(result.ok()) << aq::format_problems(result.problems);
  }
}

// "Wrong types everywhere": each value of each graph in graphs/ becomes null, a bool, a
// number, a huge number, a string, an array and an object in turn. Outside the editor's
// free-form block, a value of another kind is almost always a problem; the reader may accept
// some (a number where another number was), but must never crash, and the graph it accepts
// must validate and write back.
TEST(BadGraph, EveryValueOfEveryKindInEveryRepositoryGraph) {
  const json replacements[] = {
      nullptr,        true,          0, -1, 1e308, "text", "a.b.c", json::array(), json::array({1}),
      json::object(), json{{"x", 1}}};
  int mutations = 0, rejected = 0;
  for (const std::string& path : repository_graphs()) {
    const json original = json::parse(file_text(path));
    for_each_pointer(original, "", [&](const std::string& pointer) {
      if (pointer.rfind("/editor", 0) == 0) return;  // the editor's own, kept verbatim
      for (const json& replacement : replacements) {
        json mutated = original;
        if (mutated.at(json::json_pointer(pointer)) == replacement) continue;
        mutated[json::json_pointer(pointer)] = replacement;
        const std::string what = path + " " + pointer + " = " + replacement.dump();
        const aq::ReadResult result = aq::read_graph_text(mutated.dump(2), registry(), what);
        ++mutations;
        expect_located(result, what);
        if (!result.ok()) {
          ++rejected;
          continue;
        }
        EXPECT_TRUE(aq::validate_graph(result.graph, registry()).empty()) << what;
        const aq::ReadResult again =
            aq::read_graph_text(aq::write_graph_text(result.graph), registry());
        EXPECT_TRUE(again.ok()) << what << "\n" << aq::format_problems(again.problems);
      }
    });
  }
  EXPECT_GT(mutations, 1000);
  // Far most changes of kind must be caught (a null, an array or an object is never right
  // where a graph's value was, so at least those 5 of 11 are).
  EXPECT_GT(rejected, mutations / 2) << rejected << " of " << mutations;
}

// Every prefix of a graph file (a save cut short, a download that stopped) is a problem
// with a place, never a crash and never a graph.
TEST(BadGraph, EveryTruncationOfAGraphFileIsAProblem) {
  const std::string text = file_text(aq::test::source_path("graphs/tint.json"));
  ASSERT_GT(text.size(), 50u);
  const size_t end = text.find_last_of('}');
  for (size_t length = 0; length < end; ++length) {
    const aq::ReadResult result =
        aq::read_graph_text(text.substr(0, length), registry(), "cut.json");
    EXPECT_FALSE(result.ok()) << "prefix of " << length << " bytes was accepted";
    expect_located(result, "prefix " + std::to_string(length));
  }
}

TEST(BadGraph, DeepNestingOfObjectsAndMixedBracketsIsRefused) {
  std::string objects;
  for (int i = 0; i < 100000; ++i) objects += "{\"a\":";
  objects += "1" + std::string(100000, '}');
  std::string mixed;
  for (int i = 0; i < 50000; ++i) mixed += "[{\"a\":";
  mixed += "1";
  for (int i = 0; i < 50000; ++i) mixed += "}]";
  // Unterminated: only openings.
  const std::string open = std::string(100000, '[');
  for (const std::string* text : std::vector<const std::string*>{&objects, &mixed, &open}) {
    const aq::ReadResult result = aq::read_graph_text(*text, registry(), "deep.json");
    ASSERT_FALSE(result.ok());
    expect_located(result, "deep");
    EXPECT_NE(result.problems[0].message.find("nest deeper"), std::string::npos)
        << result.problems[0].message;
  }
  // Deep inside a node's parameter value, past the depth check's limit.
  const std::string in_param = R"({"aquarelle": 1, "nodes": {"a": {"type": "read", "params":
    {"path": )" + std::string(1000, '[') +
                               std::string(1000, ']') + R"(}}}, "output": "a.image"})";
  const aq::ReadResult param = aq::read_graph_text(in_param, registry(), "p.json");
  ASSERT_FALSE(param.ok());
  expect_located(param, "deep parameter");
}

TEST(BadGraph, LinkSourcesOfOddShapes) {
  const std::string sources[] = {
      "",  ".",        "..",       ".image",        "a.",       "a..b",  "a.b.c", "a.image",
      "a", " a.image", "a.image ", "\\u0000.image", "zz.image", "b.nope"};
  for (const std::string& source : sources) {
    const std::string text =
        R"({"aquarelle": 1, "nodes": {"a": {"type": "tint", "inputs": {"image": ")" + source +
        R"("}}, "b": {"type": "read"}}, "output": "b.image"})";
    const aq::ReadResult result = aq::read_graph_text(text, registry(), "links.json");
    // "a.image" links a to itself: a cycle. Every other source names no valid output.
    EXPECT_FALSE(result.ok()) << "source '" << source << "' was accepted";
    expect_located(result, source);
  }
  // The output may not be a node's input either, nor a node that does not exist.
  for (const std::string output : {"b", "b.", "nope.image", "b.image.image", ""}) {
    const std::string text =
        R"({"aquarelle": 1, "nodes": {"b": {"type": "read"}}, "output": ")" + output + R"("})";
    EXPECT_FALSE(aq::read_graph_text(text, registry()).ok()) << "output '" << output << "'";
  }
}

// 10,000 nodes all reading one source (wide, not a chain) validate; no timing assert here
// (the machine is shared), the limit is ctest's timeout.
TEST(BadGraph, TenThousandNodeFanOutValidates) {
  std::string text = R"({"aquarelle": 1, "nodes": {"src": {"type": "read"})";
  for (int i = 0; i < 10000; ++i) {
    text +=
        ",\n\"t" + std::to_string(i) + R"(": {"type": "tint", "inputs": {"image": "src.image"}})";
  }
  text += R"(}, "output": "t9999.image"})";
  const aq::ReadResult result = aq::read_graph_text(text, registry(), "wide.json");
  ASSERT_TRUE(result.ok()) << aq::format_problems(result.problems).substr(0, 2000);
  EXPECT_EQ(result.graph.nodes.size(), 10001u);
  EXPECT_TRUE(aq::validate_graph(result.graph, registry()).empty());
}

// 10,000 nodes each with two problems: all are reported, each with its node and place.
// Regression: each bad link used to copy every node id for its "did you mean", which made
// this file take ~25 s of CPU (quadratic); now about a second at -O0.
TEST(BadGraph, TenThousandBrokenNodesAreAllReported) {
  std::string text = R"({"aquarelle": 1, "nodes": {"src": {"type": "read"})";
  for (int i = 0; i < 10000; ++i) {
    text += ",\n\"t" + std::to_string(i) +
            R"(": {"type": "tint", "params": {"amount": "much"}, "inputs": {"image": "x.image"}})";
  }
  text += R"(}, "output": "src.image"})";
  const aq::ReadResult result = aq::read_graph_text(text, registry(), "broken.json");
  ASSERT_EQ(result.problems.size(), 20000u);
  // Printed, they are a screenful and a count, not 20,000 lines.
  const std::string printed = aq::format_problems(result.problems);
  EXPECT_EQ(std::count(printed.begin(), printed.end(), '\n'), 40);
  EXPECT_NE(printed.find("... and 19960 more problems"), std::string::npos);
  for (size_t i = 0; i < result.problems.size(); i += 997) {
    const aq::Problem& problem = result.problems[i];
    EXPECT_EQ(problem.node.substr(0, 1), "t");
    EXPECT_GT(problem.line, 1) << aq::format_problem(problem);
  }
}

// ---- Fuzzer findings (tests/fuzz): none so far; add each crash input here. ------------

}  // namespace
