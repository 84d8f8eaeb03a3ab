// The shared measuring step of the CPU-reference sweeps (see bench_reference_configs.h).
#include "bench_reference_configs.h"

#include "bench_graph_build.h"
#include "bench_measure.h"

namespace aq::app {

Status run_configs(GlContext& context, const Registry& registry, const SweepPlan& plan,
                   const std::string& type, const nlohmann::json& base_params,
                   const std::map<std::string, std::string>& inputs,
                   const std::map<std::string, ImageF>& images,
                   const std::vector<ReferenceConfig>& configs, int width, int height, Sweep* sweep,
                   const std::function<void(Graph&)>& add_sources) {
  Evaluator evaluator(context, registry);
  for (const auto& config : configs) {
    nlohmann::json params = base_params;
    for (const auto& [name, value] : config.params.items()) params[name] = value;
    Graph graph =
        single_node_graph(registry, type, params, inputs, width, height, config.precision);
    if (add_sources) add_sources(graph);
    auto measured =
        measure_node(evaluator, graph, kNodeUnderTest, &images, plan.frames, plan.warmup);
    if (!measured.ok()) {
      return make_error("sweep of '" + type + "' at " + config.setting + " (" + config.precision +
                        "): " + measured.message());
    }
    auto error = compare_images(measured->output, *config.reference);
    if (!error.ok()) {
      return make_error("sweep of '" + type + "' at " + config.setting + ": " + error.message());
    }
    SweepPoint point;
    point.setting = config.setting;
    point.params = config.params;
    point.precision = config.precision;
    point.time_ms = measured->wall_ms;
    point.gpu_ms = measured->gpu_ms;
    point.error = *error;
    sweep->points.push_back(point);
  }
  return Ok{};
}

Sweep cpu_sweep(const std::string& series, const std::string& type, const std::string& reference) {
  Sweep sweep;
  sweep.series = series;
  sweep.node_type = type;
  sweep.kind = "cpu_reference";
  sweep.reference = reference;
  sweep.time_measure = "node wall";
  return sweep;
}

}  // namespace aq::app
