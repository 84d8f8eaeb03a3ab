// The sweeps of `aquarelle bench` measured at the graph's output: quality parameters of nodes
// without a CPU reference (against the node at the sweep's highest quality in float), and the
// quality presets of the whole pipeline (against the pipeline reference render). See
// bench_sweep.h.
#include <algorithm>
#include <cstdio>
#include <string>

#include "bench_graph_build.h"
#include "bench_pipeline.h"
#include "bench_sweep.h"

namespace aq::app {

namespace {

using json = nlohmann::json;

// A quality parameter with no CPU reference: the values swept and the one taken as reference.
// `auto_param` names the node's switch that picks the value from what the camera sees (off
// for the fixed values and the reference; one more point has it on, capped by the graph's own
// value), so the sweep shows what that shortcut costs in error.
struct QualityParam {
  const char* type;
  const char* param;
  std::vector<int> values;
  int reference_value;
  const char* auto_param;
  const char* port;  // the output whose width the auto point reports
  // The node's output tiles (the caustic texture): when the graph's output is that texture
  // itself, its size follows the swept value and it is compared at the reference's size
  // after resampling with wrap-around, as a light pass sampling it with GL_REPEAT sees it.
  bool tileable;
};

const QualityParam kQualityParams[] = {
    {"shadowmap", "size", {256, 512, 1024, 2048}, 4096, "auto_size", "depth", false},
    {"caustics", "resolution", {32, 64, 128, 256}, 512, "auto_resolution", "image", true},
    {"clouds", "steps", {4, 8, 16, 32}, 256, nullptr, "image", false},
    {"control_map", "octaves", {1, 2, 3, 4}, 8, nullptr, "control", false},
    // Seed 001's murky water: fewer caustic images at successive times against all five.
    {"caustics", "blend_count", {1, 2, 3, 4}, 5, nullptr, "image", true},
};

// The pipeline reference: float precision, final quality, and each approximating node at its
// most exact setting.
Graph reference_pipeline(const Graph& graph) {
  Graph reference = graph;
  reference.settings.precision = "float";
  reference.settings.quality = "final";
  for (auto& [id, node] : reference.nodes) {
    if (node.type == "blur") {
      node.params["method"] = "gaussian";
      node.params["linear_taps"] = false;
      node.params["direct_kernel"] = "full";  // the one-pass per-pixel Gaussian, not separable
    } else if (node.type == "caustics") {
      node.params["grid"] = 1024;
      node.params["auto_grid"] = false;  // the grid asked for, whatever the texture's size
    } else if (node.type == "shadowmap") {
      node.params["size"] = 4096;
      node.params["auto_size"] = false;
    } else if (node.type == "cel_light" && node.inputs.count("surface") != 0) {
      // The packed surface holds normal and albedo in half precision; the reference reads the
      // g-buffer's own targets, in float.
      const std::string gbuffer = node.inputs.at("surface").node;
      node.inputs.erase("surface");
      for (const char* port : {"normal", "albedo", "id"})
        node.inputs[port] = PortRef{gbuffer, port};
    }
  }
  return reference;
}

// The width of `port` of `node_id` when `graph` is evaluated (what an auto setting picked).
Result<int> output_width(Evaluator& evaluator, const Graph& graph, const std::string& node_id,
                         const std::string& port) {
  EvalOptions options;
  options.frame = graph.settings.first_frame;
  auto result = evaluator.evaluate(graph, options, PortRef{node_id, port});
  if (!result.ok()) return result.error();
  return (*result)->image.width;
}

Result<Sweep> quality_param_sweep(GlContext& context, const Registry& registry, const Graph& graph,
                                  const SweepPlan& plan, const QualityParam& quality,
                                  const std::string& node_id) {
  Sweep sweep;
  sweep.series = std::string(quality.type) + " " + quality.param;
  sweep.node_type = quality.type;
  sweep.kind = "highest_quality";
  sweep.reference = "the graph's output with '" + node_id + "." + quality.param +
                    "' = " + std::to_string(quality.reference_value) + " in float precision";
  sweep.time_measure = "node wall";
  Evaluator evaluator(context, registry);
  struct Config {
    int value;  // < 0: the node picks it (auto_param on, capped by the graph's value)
    std::string precision;
  };
  auto configure = [&](const Config& config) {
    Graph g = graph;
    g.settings.width = plan.width;
    g.settings.height = plan.height;
    g.settings.precision = config.precision;
    auto& params = g.nodes[node_id].params;
    if (config.value >= 0) params[quality.param] = config.value;
    if (quality.auto_param != nullptr) params[quality.auto_param] = config.value < 0;
    return g;
  };
  auto reference = measure_node(evaluator, configure({quality.reference_value, "float"}), node_id,
                                nullptr, 0, plan.warmup);
  if (!reference.ok()) return make_error("sweep of '" + node_id + "': " + reference.message());

  std::vector<Config> configs;
  for (int value : quality.values) configs.push_back({value, graph.settings.precision});
  if (quality.auto_param != nullptr) configs.push_back({-1, graph.settings.precision});
  configs.push_back({quality.reference_value, "float"});
  for (size_t i = 0; i < configs.size(); ++i) {
    const auto& [value, precision] = configs[i];
    auto measured =
        measure_node(evaluator, configure(configs[i]), node_id, nullptr, plan.frames, plan.warmup);
    if (!measured.ok()) return make_error("sweep of '" + node_id + "': " + measured.message());
    // A graph whose output is the swept texture itself: compare at the reference's size.
    const ImageF& got = measured->output;
    const ImageF& want = reference->output;
    const bool resize = got.width != want.width || got.height != want.height;
    auto error = compare_images(
        resize ? resample_bilinear(got, want.width, want.height, quality.tileable) : got, want);
    if (!error.ok()) return make_error("sweep of '" + node_id + "': " + error.message());
    if (resize && sweep.note.empty()) {
      sweep.note =
          "the graph's output is the node's own texture, whose size follows the "
          "setting: smaller ones are compared after bilinear resampling to the "
          "reference's size" +
          std::string(quality.tileable ? " with wrap-around (GL_REPEAT)" : "");
    }
    SweepPoint point;
    if (value < 0) {
      auto picked = output_width(evaluator, configure(configs[i]), node_id, quality.port);
      if (!picked.ok()) return make_error("sweep of '" + node_id + "': " + picked.message());
      // The size it picked is in working pixels, the fixed settings are before the render
      // scale: say which.
      point.setting = std::string(quality.auto_param) + ": " + std::to_string(*picked) + " px";
      point.params = {{quality.auto_param, true}};
    } else {
      point.setting = std::string(quality.param) + "=" + std::to_string(value);
      point.params = {{quality.param, value}};
    }
    point.precision = precision;
    point.time_ms = measured->wall_ms;
    point.gpu_ms = measured->gpu_ms;
    point.error = *error;
    point.is_reference = i + 1 == configs.size();
    sweep.points.push_back(point);
  }
  return sweep;
}

// Geometry hand tremor: no approximation to trade, so its sweep shows what the effect costs
// against how far it moves the picture: amplitude at 1/4, 1/2, 1 and 2 times the graph's, each
// against the graph's output with amplitude 0 (the node hands the scene on untouched).
Result<Sweep> hand_tremor_sweep(GlContext& context, const Registry& registry, const Graph& graph,
                                const SweepPlan& plan, const std::string& node_id) {
  const double amplitude = number(graph_param(graph, registry, "hand_tremor", "amplitude"), 1.0);
  Sweep sweep;
  sweep.series = "hand_tremor amplitude";
  sweep.node_type = "hand_tremor";
  sweep.kind = "identity_reference";
  sweep.reference = "the graph's output with '" + node_id +
                    ".amplitude' = 0 (no tremor) in the same precision: the error is how far the "
                    "tremor moves the picture";
  sweep.time_measure = "node wall";
  sweep.note =
      "the node's time is its CPU work on the vertices; the meshes it moves are uploaded again "
      "by each scene reader (gbuffer, control_map), which their own times and the frame time "
      "include";
  Evaluator evaluator(context, registry);
  auto configure = [&](double value) {
    Graph g = graph;
    g.settings.width = plan.width;
    g.settings.height = plan.height;
    g.nodes[node_id].params["amplitude"] = value;
    return g;
  };
  auto still = measure_node(evaluator, configure(0.0), node_id, nullptr, 0, plan.warmup);
  if (!still.ok()) return make_error("sweep of '" + node_id + "': " + still.message());
  for (double scale : {0.25, 0.5, 1.0, 2.0}) {
    const double value = std::min(amplitude * scale, 10.0);
    auto measured =
        measure_node(evaluator, configure(value), node_id, nullptr, plan.frames, plan.warmup);
    if (!measured.ok()) return make_error("sweep of '" + node_id + "': " + measured.message());
    auto error = compare_images(measured->output, still->output);
    if (!error.ok()) return make_error("sweep of '" + node_id + "': " + error.message());
    SweepPoint point;
    char setting[64];
    std::snprintf(setting, sizeof(setting), "amplitude=%g", value);
    point.setting = setting;
    point.params = {{"amplitude", value}};
    point.precision = graph.settings.precision;
    point.time_ms = measured->wall_ms;
    point.gpu_ms = measured->gpu_ms;
    point.error = *error;
    sweep.points.push_back(point);
  }
  return sweep;
}

Result<Sweep> preset_sweep(GlContext& context, const Registry& registry, const Graph& graph,
                           const SweepPlan& plan) {
  Sweep sweep;
  sweep.series = "pipeline";
  sweep.node_type = "pipeline";
  sweep.kind = "pipeline_reference";
  sweep.reference =
      "the whole graph at quality final, float precision, exact blur taps in one pass, caustic "
      "grid 1024, "
      "shadow map 4096";
  sweep.time_measure = "frame wall";
  Graph sized = graph;
  sized.settings.width = plan.width;
  sized.settings.height = plan.height;
  Evaluator evaluator(context, registry);
  const Graph reference_graph = reference_pipeline(sized);
  auto reference = run_frames(evaluator, reference_graph, 0, 1);
  if (!reference.ok()) return make_error("pipeline reference: " + reference.message());

  struct Config {
    std::string quality, precision;
    bool is_reference;
  };
  std::vector<Config> configs;
  for (const char* quality : {"draft", "preview", "final"}) {
    for (const char* precision : {"half", "float"}) configs.push_back({quality, precision, false});
  }
  configs.push_back({"final", "float", true});
  for (const auto& config : configs) {
    Graph g = config.is_reference ? reference_graph : sized;
    g.settings.quality = config.quality;
    g.settings.precision = config.precision;
    auto run = run_frames(evaluator, g, plan.frames, plan.warmup);
    if (!run.ok()) {
      return make_error("pipeline at quality " + config.quality + ", " + config.precision + ": " +
                        run.message());
    }
    auto error = compare_images(run->first, reference->first);
    if (!error.ok()) return make_error("pipeline: " + error.message());
    SweepPoint point;
    point.setting = config.is_reference ? "reference" : "quality=" + config.quality;
    point.params = {{"quality", config.quality}};
    point.precision = config.precision;
    point.time_ms = run->frame_ms;
    point.error = *error;
    point.is_reference = config.is_reference;
    sweep.points.push_back(point);
  }
  return sweep;
}

}  // namespace

Result<std::vector<Sweep>> run_graph_sweeps(GlContext& context, const Registry& registry,
                                            const Graph& graph, const SweepPlan& plan,
                                            const std::set<std::string>& types) {
  std::vector<Sweep> sweeps;
  for (const auto& quality : kQualityParams) {
    if (types.count(quality.type) == 0) continue;
    const std::string node_id = first_node_of_type(graph, quality.type);
    if (node_id.empty()) continue;  // measured at the graph's output: needs the node in it
    auto sweep = quality_param_sweep(context, registry, graph, plan, quality, node_id);
    if (!sweep.ok()) return sweep.error();
    sweeps.push_back(*sweep);
  }
  if (types.count("hand_tremor") > 0 && !first_node_of_type(graph, "hand_tremor").empty()) {
    auto sweep =
        hand_tremor_sweep(context, registry, graph, plan, first_node_of_type(graph, "hand_tremor"));
    if (!sweep.ok()) return sweep.error();
    sweeps.push_back(*sweep);
  }
  if (types.count("scene") > 0 && !first_node_of_type(graph, "scene").empty()) {
    const json iterations = graph_param(graph, registry, "scene", "smoothing");
    auto sweep = smoothing_sweep(plan, iterations.is_number() ? iterations.get<int>() : -1);
    if (!sweep.ok()) return sweep.error();
    sweeps.push_back(*sweep);
  }
  auto deep_ocean = run_deep_ocean_sweeps(context, registry, graph, plan, types);
  if (!deep_ocean.ok()) return deep_ocean.error();
  sweeps.insert(sweeps.end(), deep_ocean->begin(), deep_ocean->end());
  if (plan.pipeline) {
    auto sweep = preset_sweep(context, registry, graph, plan);
    if (!sweep.ok()) return sweep.error();
    sweeps.push_back(*sweep);
  }
  return sweeps;
}

}  // namespace aq::app
