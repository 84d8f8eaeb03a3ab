// Whole-graph timing for `aquarelle bench` (see bench_pipeline.h).
#include "bench_pipeline.h"

#include <algorithm>
#include <chrono>
#include <map>

namespace aq::app {

namespace {

double elapsed_ms(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start)
      .count();
}

}  // namespace

Result<PipelineTiming> time_pipeline(GlContext& context, const Registry& registry,
                                     const Graph& graph, const TimingPlan& plan) {
  PipelineTiming timing;
  timing.retain_outputs = plan.retain_outputs;
  Evaluator evaluator(context, registry);
  const int first = graph.settings.first_frame;

  // Per node, one sample per timed frame (0 when reused), in evaluation order.
  std::vector<std::string> order;
  std::map<std::string, NodeStats> stats;
  std::map<std::string, std::vector<double>> gpu, cpu;
  std::vector<double> wall_sums;
  for (int i = 0; i < plan.warmup + plan.frames; ++i) {
    EvalOptions options;
    options.frame = first + i;
    options.retain_outputs = plan.retain_outputs;
    options.measure_gpu_time = true;
    options.finish_each_node = true;
    auto result = evaluator.evaluate(graph, options);
    if (!result.ok())
      return make_error("frame " + std::to_string(options.frame) + ": " + result.message());
    if (i < plan.warmup) continue;
    double wall_sum = 0;
    for (const auto& t : evaluator.last_timings()) {
      auto [it, inserted] = stats.try_emplace(t.node);
      if (inserted) {
        order.push_back(t.node);
        it->second.id = t.node;
        it->second.type = t.type;
      }
      if (!t.cached) ++it->second.runs;
      gpu[t.node].push_back(t.gpu_ms);
      cpu[t.node].push_back(t.cpu_ms);
      wall_sum += t.cpu_ms;
    }
    wall_sums.push_back(wall_sum);
  }
  for (const auto& id : order) {
    NodeStats node = stats[id];
    node.gpu_ms = summarize(gpu[id]);
    node.wall_ms = summarize(cpu[id]);
    timing.nodes.push_back(node);
  }
  timing.node_wall_sum_ms = summarize(wall_sums);

  // The frame cost without the timer queries' waits, in a fresh evaluator so the same frames
  // are evaluated from the same state.
  Evaluator untimed(context, registry);
  std::vector<double> frame_ms;
  for (int i = 0; i < plan.warmup + plan.frames; ++i) {
    EvalOptions options;
    options.frame = first + i;
    options.retain_outputs = plan.retain_outputs;
    options.measure_gpu_time = false;
    glFinish();
    auto start = std::chrono::steady_clock::now();
    {
      auto result = untimed.evaluate(graph, options);
      if (!result.ok())
        return make_error("frame " + std::to_string(options.frame) + ": " + result.message());
      glFinish();
    }
    if (i >= plan.warmup) frame_ms.push_back(elapsed_ms(start));
  }
  timing.frame_ms = summarize(frame_ms);
  return timing;
}

Result<FrameRun> run_frames(Evaluator& evaluator, const Graph& graph, int frames, int warmup) {
  FrameRun run;
  const int first = graph.settings.first_frame;
  std::vector<double> frame_ms;
  for (int i = 0; i < std::max(warmup, 1) + frames; ++i) {
    EvalOptions options;
    options.frame = first + i;
    options.retain_outputs = true;
    options.measure_gpu_time = false;
    glFinish();
    auto start = std::chrono::steady_clock::now();
    auto result = evaluator.evaluate(graph, options);
    if (!result.ok())
      return make_error("frame " + std::to_string(options.frame) + ": " + result.message());
    glFinish();
    const double ms = elapsed_ms(start);
    if (i == 0) {
      auto pixels = evaluator.read_back(*result);
      if (!pixels.ok()) return pixels.error();
      run.first = std::move(*pixels);
    }
    if (i >= std::max(warmup, 1)) frame_ms.push_back(ms);
  }
  run.frame_ms = summarize(frame_ms);
  return run;
}

}  // namespace aq::app
