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

namespace {

// Per-node samples of one mode, one per timed frame (0 when the node was reused).
struct NodeSamples {
  std::vector<std::string> order;
  std::map<std::string, NodeStats> stats;
  std::map<std::string, std::vector<double>> wall, gpu;
  std::vector<double> wall_sums;

  void add(const std::vector<NodeTiming>& timings) {
    double wall_sum = 0;
    for (const auto& t : timings) {
      auto [it, inserted] = stats.try_emplace(t.node);
      if (inserted) {
        order.push_back(t.node);
        it->second.id = t.node;
        it->second.type = t.type;
      }
      if (!t.cached && !t.fused) ++it->second.runs;
      if (t.fused) it->second.fused = true;
      wall[t.node].push_back(t.cpu_ms);
      gpu[t.node].push_back(t.gpu_ms);
      wall_sum += t.cpu_ms;
    }
    wall_sums.push_back(wall_sum);
  }
  void finish(PipelineTiming* timing) {
    for (const auto& id : order) {
      NodeStats node = stats[id];
      node.wall_ms = summarize(wall[id]);
      node.gpu_ms = summarize(gpu[id]);
      timing->nodes.push_back(node);
    }
    timing->node_wall_sum_ms = summarize(wall_sums);
  }
};

Status frame_error(int frame, const Result<TextureRef>& result) {
  return make_error("frame " + std::to_string(frame) + ": " + result.message());
}

// One frame's wall time, evaluate() + glFinish, with node timing off (timer queries make the CPU
// wait for each node, which would inflate the frame); outputs not kept except static nodes' when
// `retain_static` (as `aquarelle render` runs).
struct TimedFrame {
  TextureRef output;
  double ms = 0;
};
Result<TimedFrame> timed_frame(Evaluator& evaluator, const Graph& graph, int frame,
                               bool retain_static) {
  EvalOptions options;
  options.frame = frame;
  options.retain_outputs = false;
  options.retain_static_outputs = retain_static;
  options.measure_gpu_time = false;
  glFinish();
  const auto start = std::chrono::steady_clock::now();
  auto result = evaluator.evaluate(graph, options);
  if (!result.ok()) return frame_error(frame, result).error();
  glFinish();
  return TimedFrame{*result, elapsed_ms(start)};
}

}  // namespace

Result<PipelineTimings> time_pipeline(GlContext& context, const Registry& registry,
                                      const Graph& graph, const TimingPlan& plan,
                                      CopyPass& copy_pass) {
  PipelineTimings timings;
  timings.every_node_runs.static_cached = false;
  timings.cached.static_cached = true;
  const int first = graph.settings.first_frame;

  // Per-node times: each node's process() between two glFinish calls.
  {
    Evaluator every(context, registry), cached(context, registry);
    NodeSamples every_samples, cached_samples;
    for (int i = 0; i < plan.warmup + plan.frames; ++i) {
      for (bool retain : {false, true}) {
        EvalOptions options;
        options.frame = first + i;
        options.retain_outputs = false;
        options.retain_static_outputs = retain;
        options.measure_gpu_time = true;
        options.finish_each_node = true;
        Evaluator& evaluator = retain ? cached : every;
        auto result = evaluator.evaluate(graph, options);
        if (!result.ok()) return frame_error(options.frame, result).error();
        if (i >= plan.warmup)
          (retain ? cached_samples : every_samples).add(evaluator.last_timings());
      }
    }
    every_samples.finish(&timings.every_node_runs);
    cached_samples.finish(&timings.cached);
  }

  // Frame times without the per-node waits and timer queries, which would inflate the frame;
  // fresh evaluators so the same frames are evaluated from the same state.
  Evaluator every(context, registry), cached(context, registry);
  std::vector<double> every_ms, cached_ms;
  for (int i = 0; i < plan.warmup + plan.frames; ++i) {
    for (bool retain : {false, true}) {
      auto frame = timed_frame(retain ? cached : every, graph, first + i, retain);
      if (!frame.ok()) return frame.error();
      if (i < plan.warmup) continue;
      (retain ? cached_ms : every_ms).push_back(frame->ms);
      timings.copy_samples.push_back(copy_pass.run_batch());
    }
  }
  timings.every_node_runs.frame_ms = summarize(every_ms);
  timings.cached.frame_ms = summarize(cached_ms);
  return timings;
}

Result<SideBySide> time_side_by_side(GlContext& context, const Registry& registry,
                                     const Graph& graph, const Graph& baseline,
                                     const TimingPlan& plan) {
  Evaluator graph_evaluator(context, registry), baseline_evaluator(context, registry);
  std::vector<double> graph_ms, baseline_ms, ratios;
  for (int i = 0; i < plan.warmup + plan.frames; ++i) {
    // Which graph goes first alternates, so neither always follows the other's frame.
    double pair[2] = {0.0, 0.0};
    for (int k = 0; k < 2; ++k) {
      const bool is_graph = (k == 0) == (i % 2 == 0);
      const Graph& g = is_graph ? graph : baseline;
      auto frame = timed_frame(is_graph ? graph_evaluator : baseline_evaluator, g,
                               g.settings.first_frame + i, true);
      if (!frame.ok()) return make_error((is_graph ? "" : "baseline: ") + frame.message());
      pair[is_graph ? 0 : 1] = frame->ms;
    }
    if (i < plan.warmup) continue;
    graph_ms.push_back(pair[0]);
    baseline_ms.push_back(pair[1]);
    ratios.push_back(pair[1] > 0.0 ? pair[0] / pair[1] : 0.0);
  }
  return SideBySide{summarize(graph_ms), summarize(baseline_ms), summarize(ratios)};
}

Result<FrameRun> run_frames(Evaluator& evaluator, const Graph& graph, int frames, int warmup) {
  FrameRun run;
  const int first = graph.settings.first_frame;
  std::vector<double> frame_ms;
  for (int i = 0; i < std::max(warmup, 1) + frames; ++i) {
    auto frame = timed_frame(evaluator, graph, first + i, true);
    if (!frame.ok()) return frame.error();
    if (i == 0) {
      auto pixels = evaluator.read_back(frame->output);
      if (!pixels.ok()) return pixels.error();
      run.first = std::move(*pixels);
    }
    if (i >= std::max(warmup, 1)) frame_ms.push_back(frame->ms);
  }
  run.frame_ms = summarize(frame_ms);
  return run;
}

}  // namespace aq::app
