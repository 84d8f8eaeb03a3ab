// Test harness: a headless context per backend kept until the last test, the build's plugins, and
// helpers to run nodes and graphs and compare images. See harness.h.
#include "support/harness.h"

#include <aquarelle/core/evaluator.h>
#include <aquarelle/core/gl_context.h>
#include <aquarelle/core/graph_io.h>
#include <aquarelle/core/plugin_loader.h>

#include <cmath>
#include <cstdio>
#include <memory>
#include <random>

namespace aq::test {

namespace {

struct Loaded {
  Registry registry;
  PluginSet plugins;
};

Loaded& loaded() {
  static Loaded* instance = [] {
    auto* l = new Loaded();
    register_builtin_nodes(l->registry);
    auto report = l->plugins.load({AQ_PLUGIN_BUILD_DIR}, l->registry);
    for (const auto& refused : report.refused) {
      std::fprintf(stderr, "harness: plugin refused: %s\n", refused.c_str());
    }
    return l;
  }();
  return *instance;
}

struct Backend {
  std::unique_ptr<GlContext> context;
  std::unique_ptr<Evaluator> evaluator;
  std::string error;
};

// Contexts and evaluators live until the last test has run: shutdown() (called by main() in
// test_main.cpp) destroys them then, before exit and LeakSanitizer's check, and not from
// static destructors, where the drivers may already have torn down their own state.
std::map<std::string, Backend*>& backends() {
  static auto* backends = new std::map<std::string, Backend*>();
  return *backends;
}

void destroy_backend(Backend* b) {
  b->evaluator.reset();  // activates its context to delete its GL objects: before the context
  b->context.reset();
  delete b;
}

Backend& backend(const std::string& name) {
  auto it = backends().find(name);
  if (it != backends().end()) return *it->second;
  // One GL implementation at a time, as in `aquarelle render` and the editor: a test that
  // switches between EGL and OSMesa gets a fresh context for each, so no GL state of one
  // implementation (current context, dispatch) is ever resumed after the other's ran.
  for (auto& [other, b] : backends()) destroy_backend(b);
  backends().clear();
  auto* b = new Backend();
  auto parsed = parse_backend(name);
  if (!parsed.ok()) {
    b->error = parsed.message();
  } else {
    auto context = create_headless_context(*parsed);
    if (!context.ok()) {
      b->error = context.message();
    } else {
      b->context = std::move(*context);
      b->evaluator = std::make_unique<Evaluator>(*b->context, loaded().registry);
    }
  }
  backends()[name] = b;
  return *b;
}

}  // namespace

const Registry& registry() {
  return loaded().registry;
}

void shutdown() {
  for (auto& [name, b] : backends()) destroy_backend(b);
  backends().clear();
}

std::string source_path(const std::string& relative) {
  return std::string(AQ_SOURCE_DIR) + "/" + relative;
}

static Result<ImageF> render(Graph graph, const RenderOptions& options,
                             const std::map<std::string, ImageF>& images) {
  Backend& b = backend(options.gl);
  if (!b.evaluator) return make_error("no " + options.gl + " context: " + b.error);
  graph.settings.width = options.width;
  graph.settings.height = options.height;
  graph.settings.precision = options.precision;
  graph.settings.quality = options.quality;
  graph.settings.fps = options.fps;
  std::optional<PortRef> output;
  if (!options.output.empty()) {
    output = PortRef::parse(options.output);
    if (!output) return make_error("bad output '" + options.output + "'");
  }
  EvalOptions eval;
  eval.frame = options.frame;
  eval.images = &images;
  eval.retain_outputs = false;
  eval.retain_static_outputs = false;  // every call really runs every node: tests compare runs
  eval.fuse_pointwise = options.fuse_pointwise;
  auto texture = b.evaluator->evaluate(graph, eval, output);
  if (!texture.ok()) return texture.error();
  return b.evaluator->read_back(*texture);
}

Result<ImageF> render_graph(const std::string& json_text, const RenderOptions& options,
                            const std::map<std::string, ImageF>& images) {
  ReadResult read = read_graph_text(json_text, registry(), "test graph");
  if (!read.ok()) return make_error(format_problems(read.problems));
  return render(std::move(read.graph), options, images);
}

Result<ImageF> render_graph_file(const std::string& path, const RenderOptions& options) {
  ReadResult read = read_graph_file(path, registry());
  if (!read.ok()) return make_error(format_problems(read.problems));
  return render(std::move(read.graph), options, {});
}

Result<ImageF> run_node(const std::string& type_name, const std::map<std::string, ImageF>& inputs,
                        const nlohmann::json& params, const RenderOptions& options) {
  const NodeType* type = registry().find(type_name);
  if (type == nullptr) return make_error("node type '" + type_name + "' is not installed");
  Graph graph;
  Node node;
  node.type = type_name;
  if (params.is_object()) {
    for (auto it = params.begin(); it != params.end(); ++it) node.params[it.key()] = it.value();
  }
  for (const auto& [port, image] : inputs) {
    if (type->input(port) == nullptr) {
      return make_error("node type '" + type_name + "' has no input '" + port + "'");
    }
    Node source;
    source.type = "image_input";
    source.params["name"] = port;
    graph.nodes["in_" + port] = source;
    node.inputs[port] = PortRef{"in_" + port, "image"};
  }
  graph.nodes["node"] = node;
  std::string port = type->outputs.empty() ? "image" : type->outputs[0].name;
  if (!options.output.empty()) port = options.output;
  RenderOptions adjusted = options;
  adjusted.output = "node." + port;
  return render(std::move(graph), adjusted, inputs);
}

namespace {
int channel_count(const ImageF& a, const ImageF& b, int channels) {
  int c = std::min(a.channels, b.channels);
  return channels < 0 ? c : std::min(c, channels);
}
bool same_size(const ImageF& a, const ImageF& b) {
  return a.width == b.width && a.height == b.height;
}
}  // namespace

double max_abs_diff(const ImageF& a, const ImageF& b, int channels) {
  if (!same_size(a, b)) return INFINITY;
  int n = channel_count(a, b, channels);
  double worst = 0;
  for (int y = 0; y < a.height; ++y) {
    for (int x = 0; x < a.width; ++x) {
      for (int c = 0; c < n; ++c) {
        double d = std::abs(static_cast<double>(a.at(x, y, c)) - b.at(x, y, c));
        if (!(d <= worst)) worst = d;  // NaN propagates as the worst
      }
    }
  }
  return worst;
}

double mean_abs_diff(const ImageF& a, const ImageF& b, int channels) {
  if (!same_size(a, b)) return INFINITY;
  int n = channel_count(a, b, channels);
  double sum = 0;
  for (int y = 0; y < a.height; ++y) {
    for (int x = 0; x < a.width; ++x) {
      for (int c = 0; c < n; ++c)
        sum += std::abs(static_cast<double>(a.at(x, y, c)) - b.at(x, y, c));
    }
  }
  return sum / (static_cast<double>(a.width) * a.height * n);
}

double psnr(const ImageF& a, const ImageF& b, double peak, int channels) {
  if (!same_size(a, b)) return 0;
  int n = channel_count(a, b, channels);
  double sum = 0;
  for (int y = 0; y < a.height; ++y) {
    for (int x = 0; x < a.width; ++x) {
      for (int c = 0; c < n; ++c) {
        double d = static_cast<double>(a.at(x, y, c)) - b.at(x, y, c);
        sum += d * d;
      }
    }
  }
  double mse = sum / (static_cast<double>(a.width) * a.height * n);
  if (mse == 0) return INFINITY;
  return 10.0 * std::log10(peak * peak / mse);
}

bool all_finite(const ImageF& image) {
  for (float v : image.pixels) {
    if (!std::isfinite(v)) return false;
  }
  return true;
}

ImageF gradient_image(int width, int height) {
  ImageF image(width, height, 4);
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) {
      float u = (x + 0.5f) / width, v = (y + 0.5f) / height;
      image.at(x, y, 0) = u;
      image.at(x, y, 1) = v;
      image.at(x, y, 2) = 1.0f - u;
      image.at(x, y, 3) = 1.0f;
    }
  }
  return image;
}

Result<ImageF> evaluate_text(Evaluator& evaluator, const std::string& json_text, int frame,
                             const std::function<void(Graph&)>& adjust,
                             const std::map<std::string, ImageF>* images) {
  ReadResult read = read_graph_text(json_text, registry(), "test graph");
  if (!read.ok()) return make_error(format_problems(read.problems));
  if (adjust) adjust(read.graph);
  EvalOptions options;
  options.frame = frame;
  options.images = images;
  auto out = evaluator.evaluate(read.graph, options);
  if (!out.ok()) return out.error();
  return evaluator.read_back(*out);
}

std::string wobble_edge_pigment_graph(const nlohmann::json& pigment_params,
                                      const std::string& tail_id, nlohmann::json tail) {
  tail["inputs"]["image"] = "pigment.image";
  nlohmann::json graph = {
      {"aquarelle", 1},
      {"nodes",
       {{"input", {{"type", "image_input"}, {"params", {{"name", "image"}}}}},
        {"cells", {{"type", "noise"}, {"params", {{"type", "worley"}, {"scale", 8}, {"seed", 3}}}}},
        {"canvas", {{"type", "pigment_canvas"}, {"params", {{"grain_frequency", 32.0}}}}},
        {"wobble",
         {{"type", "wobble"},
          {"params", {{"strength", 6.0}}},
          {"inputs", {{"image", "input.image"}}}}},
        {"edge",
         {{"type", "edge"},
          {"params", {{"threshold", 0.05}, {"softness", 0.2}, {"factor", 0.5}}},
          {"inputs", {{"image", "wobble.image"}, {"source", "cells.image"}}}}},
        {"pigment",
         {{"type", "pigment_apply"},
          {"params", pigment_params},
          {"inputs", {{"image", "edge.image"}, {"density", "canvas.density"}}}}},
        {tail_id, tail}}},
      {"output", tail_id + ".image"}};
  return graph.dump();
}

std::pair<NodeType, std::string> describe_node(const aq_port_desc* input,
                                               const aq_port_desc* output, uint32_t flags,
                                               const aq_pointwise_desc* pointwise) {
  aq_node_desc desc{};
  desc.struct_size = sizeof(aq_node_desc);
  desc.type_name = "described";
  desc.category = "Filter";
  desc.description = "test";
  desc.flags = flags;
  desc.inputs = input;
  desc.input_count = 1;
  desc.outputs = output;
  desc.output_count = 1;
  desc.create = [](const aq_host*) -> void* { return nullptr; };
  desc.destroy = [](void*) {};
  desc.process = [](void*, aq_process_ctx*) { return int{AQ_OK}; };
  desc.pointwise = pointwise;
  std::string why;
  NodeType type = node_type_from_desc(desc, "test.so", &why);
  return {std::move(type), why};
}

ImageF random_image(int width, int height, unsigned seed, float lo, float hi) {
  ImageF image(width, height, 4);
  // A fixed LCG rather than <random> distributions, whose output is implementation-defined.
  uint64_t state = seed * 6364136223846793005ull + 1442695040888963407ull;
  for (size_t i = 0; i < image.pixels.size(); ++i) {
    state = state * 6364136223846793005ull + 1442695040888963407ull;
    double unit = static_cast<double>(state >> 11) / 9007199254740992.0;
    image.pixels[i] = (i % 4 == 3) ? 1.0f : static_cast<float>(lo + (hi - lo) * unit);
  }
  return image;
}

ImageF constant_image(int width, int height, float r, float g, float b, float a) {
  ImageF image(width, height, 4);
  for (size_t i = 0; i < image.pixels.size(); i += 4) {
    image.pixels[i] = r;
    image.pixels[i + 1] = g;
    image.pixels[i + 2] = b;
    image.pixels[i + 3] = a;
  }
  return image;
}

ImageF checker_image(int width, int height, int cell) {
  ImageF image(width, height, 4);
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) {
      float v = ((x / cell + y / cell) % 2 == 0) ? 1.0f : 0.0f;
      for (int c = 0; c < 3; ++c) image.at(x, y, c) = v;
      image.at(x, y, 3) = 1.0f;
    }
  }
  return image;
}

}  // namespace aq::test
