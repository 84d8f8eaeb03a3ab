// libFuzzer target for the graph reader and validator: any bytes given to read_graph_text must
// come back as a graph or as problems, never as a crash, a hang or an exception, and a graph
// read without problems must survive write -> read unchanged (the writer's canonical text is
// a fixed point) and validate_graph must agree that it is valid.
//
// The registry holds the host's `read` and `image_input` shapes (rebuilt here: the real ones
// live with OpenImageIO in builtin_nodes.cpp), a few fake types that use every port and
// parameter type, and the plugins found on $AQUARELLE_PLUGIN_PATH, so the seed graphs from
// graphs/*.json reach the parameter and link checks rather than stopping at "unknown type".
// Built by tests/fuzz/CMakeLists.txt (a separate clang project), run by scripts/fuzz.sh.
#include <aquarelle/core/graph_io.h>
#include <aquarelle/core/plugin_loader.h>
#include <aquarelle/core/registry.h>

#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <sstream>
#include <string>

namespace {

aq::ParamInfo param(const std::string& name, aq_param_type type, double min_value = 0,
                    double max_value = 0) {
  aq::ParamInfo info;
  info.name = name;
  info.type = type;
  info.min_value = min_value;
  info.max_value = max_value;
  return info;
}

aq::NodeType source_type(const std::string& name, const std::string& string_param) {
  aq::NodeType type;
  type.name = name;
  type.category = "Input";
  type.outputs = {aq::PortInfo{"image", AQ_PORT_IMAGE, false, ""}};
  aq::ParamInfo text = param(string_param, name == "read" ? AQ_PARAM_PATH : AQ_PARAM_STRING);
  type.params = {text};
  if (name == "read") type.params.push_back(param("colorspace", AQ_PARAM_STRING));
  type.plugin_file = "(fuzzer)";
  return type;
}

// Every port and parameter type, optional and required inputs, ranges and an enum.
aq::NodeType everything_type() {
  aq::NodeType type;
  type.name = "fuzz_everything";
  type.category = "Fuzz";
  type.inputs = {aq::PortInfo{"image", AQ_PORT_IMAGE, false, ""},
                 aq::PortInfo{"mask", AQ_PORT_IMAGE, true, ""},
                 aq::PortInfo{"scene", AQ_PORT_SCENE, true, ""}};
  type.outputs = {aq::PortInfo{"image", AQ_PORT_IMAGE, false, ""},
                  aq::PortInfo{"scene", AQ_PORT_SCENE, false, ""}};
  type.params = {param("f", AQ_PARAM_FLOAT, -10, 10),
                 param("i", AQ_PARAM_INT, -5, 5),
                 param("b", AQ_PARAM_BOOL),
                 param("v3", AQ_PARAM_VEC3, -1, 1),
                 param("c", AQ_PARAM_COLOR, 0, 1),
                 param("s", AQ_PARAM_STRING),
                 param("p", AQ_PARAM_PATH)};
  aq::ParamInfo choice = param("e", AQ_PARAM_ENUM);
  choice.enum_values = {"one", "two", "three"};
  choice.default_string = "one";
  type.params.push_back(choice);
  type.plugin_file = "(fuzzer)";
  return type;
}

const aq::Registry& registry() {
  static aq::Registry* instance = [] {
    auto* made = new aq::Registry();
    std::string why;
    made->add(source_type("read", "path"), &why);
    made->add(source_type("image_input", "name"), &why);
    made->add(everything_type(), &why);
    // Plugins only from the environment's plugin path: the build folder compiled into
    // plugin_loader.cpp may not exist where the fuzzer runs.
    std::vector<std::string> directories;
    if (const char* env = std::getenv("AQUARELLE_PLUGIN_PATH"); env != nullptr) {
      std::stringstream stream(env);
      std::string item;
      while (std::getline(stream, item, ':')) {
        if (!item.empty()) directories.push_back(item);
      }
    }
    static aq::PluginSet plugins;  // keeps the libraries' descriptions mapped
    const aq::PluginLoadReport report = plugins.load(directories, *made);
    std::fprintf(stderr, "graph_reader_fuzzer: %zu node types (%zu plugin files, %zu refused)\n",
                 made->types().size(), report.loaded.size(), report.refused.size());
    return made;
  }();
  return *instance;
}

[[noreturn]] void fail(const char* what, const std::string& detail) {
  std::fprintf(stderr, "graph_reader_fuzzer: %s\n%s\n", what, detail.c_str());
  std::abort();
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  const aq::Registry& types = registry();
  aq::ReadResult first = aq::read_graph_text(text, types, "fuzz.json");
  // Formatting must work for every problem the reader can make.
  const std::string report = aq::format_problems(first.problems);
  for (const aq::Problem& problem : first.problems) {
    if (problem.message.empty()) fail("a problem without a message", report);
  }
  if (!first.ok()) return 0;

  const std::vector<aq::Problem> model_problems = aq::validate_graph(first.graph, types);
  if (!model_problems.empty()) {
    fail("read_graph_text accepted a graph that validate_graph rejects",
         aq::format_problems(model_problems) + "\n--- input ---\n" + text);
  }
  const std::string written = aq::write_graph_text(first.graph);
  aq::ReadResult second = aq::read_graph_text(written, types, "fuzz.json");
  if (!second.ok()) {
    fail("the writer's text of a valid graph does not read back",
         aq::format_problems(second.problems) + "\n--- written ---\n" + written);
  }
  const std::string rewritten = aq::write_graph_text(second.graph);
  if (rewritten != written) {
    fail("write -> read -> write is not a fixed point",
         "--- first ---\n" + written + "--- second ---\n" + rewritten);
  }
  return 0;
}
