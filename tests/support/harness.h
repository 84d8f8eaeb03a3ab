// Test support: one headless GL context per test process, every plugin of the build loaded,
// and short calls that run a node or a graph and read the result back as float pixels.
//
//   auto out = aq::test::run_node("tint", {{"image", input}}, {{"amount", 0.5}});
//   ASSERT_TRUE(out.ok()) << out.message();
//   EXPECT_LT(aq::test::max_abs_diff(*out, reference), 1e-4);
//
// Images fed to a node go through the host's built-in `image_input` node type, which uploads
// a CPU image (ImageF, row 0 at the bottom) as an RGBA32F texture.
#pragma once

#include <aquarelle/core/graph.h>
#include <aquarelle/core/image.h>
#include <aquarelle/core/registry.h>
#include <aquarelle/core/result.h>

#include <nlohmann/json.hpp>

#include <functional>
#include <map>
#include <string>
#include <utility>

namespace aq {
class Evaluator;
}

namespace aq::test {

struct RenderOptions {
  int width = 64;  // the graph's resolution (ctx.width/height for nodes that use it)
  int height = 64;
  int frame = 1;
  double fps = 24.0;
  std::string precision = "float";  // "half" or "float"
  std::string quality = "final";
  std::string gl = "egl";      // "egl" or "osmesa"
  std::string output;          // "node.port"; empty: the graph's output / node's first
  bool fuse_pointwise = true;  // EvalOptions::fuse_pointwise
};

// Every plugin in the build's plugin folder plus the host's built-in types.
const Registry& registry();

// Destroys the evaluators and GL contexts made so far (each evaluator before its context); a
// later call makes new ones. Runs by itself after the last test (test_main.cpp), so that leak
// checking at exit sees them freed. The registry and the plugins stay loaded until exit (their
// code must stay mapped for a leak report to name it).
void shutdown();

// Renders a graph given as JSON text (the file format). `images` feeds `image_input` nodes
// by their `name` parameter.
Result<ImageF> render_graph(const std::string& json_text, const RenderOptions& options = {},
                            const std::map<std::string, ImageF>& images = {});
Result<ImageF> render_graph_file(const std::string& path, const RenderOptions& options = {});

// Runs one node of `type` with CPU images on its image inputs and `params`; returns the output
// named by options.output's port (or its first output).
Result<ImageF> run_node(const std::string& type, const std::map<std::string, ImageF>& inputs,
                        const nlohmann::json& params = nlohmann::json::object(),
                        const RenderOptions& options = {});

// Comparisons over the first `channels` channels (all when -1).
double max_abs_diff(const ImageF& a, const ImageF& b, int channels = -1);
double mean_abs_diff(const ImageF& a, const ImageF& b, int channels = -1);
double psnr(const ImageF& a, const ImageF& b, double peak = 1.0, int channels = -1);
bool all_finite(const ImageF& image);

// Small deterministic test images.
ImageF gradient_image(int width, int height);  // r = x, g = y, b = 1 - x, a = 1
ImageF random_image(int width, int height, unsigned seed, float lo = 0.0f, float hi = 1.0f);
ImageF constant_image(int width, int height, float r, float g, float b, float a = 1.0f);
ImageF checker_image(int width, int height, int cell);

// Evaluates a graph given as JSON text at `frame` with an evaluator of the test's own (node
// instances and what they keep stay between calls, unlike render_graph's), after `adjust` may
// change the graph read (settings, parameters), and reads the output back.
Result<ImageF> evaluate_text(Evaluator& evaluator, const std::string& json_text, int frame,
                             const std::function<void(Graph&)>& adjust = {},
                             const std::map<std::string, ImageF>* images = nullptr);

// The flagship's chain on the image input "image": wobble → edge (detecting on Worley cells) →
// pigment_apply (density from a pigment_canvas, `pigment_params`) → the node `tail_id`
// (`tail`, a node whose `image` input the chain feeds), which is the output.
std::string wobble_edge_pigment_graph(const nlohmann::json& pigment_params,
                                      const std::string& tail_id, nlohmann::json tail);

// Path of a file in the source tree (e.g. "graphs/tint.json").
std::string source_path(const std::string& relative);

// What the registry makes of a node with one input and one output port (the type, or empty with
// the reason it refuses it): for tests of port and node flags. Its create/process do nothing.
std::pair<NodeType, std::string> describe_node(const aq_port_desc* input,
                                               const aq_port_desc* output, uint32_t flags = 0,
                                               const aq_pointwise_desc* pointwise = nullptr);

}  // namespace aq::test
