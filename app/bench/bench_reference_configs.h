// Running one node type at several configurations against CPU reference images, the step every
// sweep with a double-precision reference shares (bench_reference_sweeps.cpp,
// bench_layered_sweeps.cpp): a graph of the node alone, measured and compared per configuration.
#pragma once

#include <aquarelle/core/gl_context.h>
#include <aquarelle/core/image.h>
#include <aquarelle/core/registry.h>
#include <aquarelle/core/result.h>

#include <nlohmann/json.hpp>

#include <chrono>
#include <functional>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "bench_sweep.h"

namespace aq::app {

// One point of a sweep: the node's parameters on top of the sweep's, its precision and the
// reference image its output is compared with.
struct ReferenceConfig {
  std::string setting;
  nlohmann::json params;
  std::string precision;
  std::shared_ptr<const ImageF> reference;
};

// An empty sweep of `type` against a CPU reference (kind cpu_reference, node wall time).
Sweep cpu_sweep(const std::string& series, const std::string& type, const std::string& reference);

// Times a CPU reference computation, adding its milliseconds to `total_ms`.
template <typename F>
std::shared_ptr<const ImageF> timed_reference(double* total_ms, F&& compute) {
  const auto start = std::chrono::steady_clock::now();
  auto image = std::make_shared<const ImageF>(compute());
  *total_ms +=
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  return image;
}

// Runs every configuration of one node type (fed `images` through `inputs`) and adds a point
// with its time and its error against the configuration's reference to `sweep`. `add_sources`,
// when given, completes each graph before it runs (a node's non-image inputs, e.g. a scene).
Status run_configs(GlContext& context, const Registry& registry, const SweepPlan& plan,
                   const std::string& type, const nlohmann::json& base_params,
                   const std::map<std::string, std::string>& inputs,
                   const std::map<std::string, ImageF>& images,
                   const std::vector<ReferenceConfig>& configs, int width, int height, Sweep* sweep,
                   const std::function<void(Graph&)>& add_sources = {});

}  // namespace aq::app
