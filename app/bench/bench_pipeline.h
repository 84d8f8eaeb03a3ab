// Per-node and per-frame timing of a whole graph for `aquarelle bench`, in the two ways a
// pipeline can run: every node re-runs each frame (outputs are not kept), or unchanged nodes
// are reused from the previous frame (what an animation with static parts really costs).
#pragma once

#include <aquarelle/core/evaluator.h>
#include <aquarelle/core/gl_context.h>
#include <aquarelle/core/graph.h>
#include <aquarelle/core/registry.h>
#include <aquarelle/core/result.h>

#include <string>
#include <vector>

#include "bench_copy_pass.h"
#include "bench_stats.h"

namespace aq::app {

struct NodeStats {
  std::string id;
  std::string type;
  // Per frame, 0 on frames where the node was reused. wall_ms: process() with glFinish before
  // and after, so it holds the node's GPU work (the figure to quote on llvmpipe); gpu_ms: the
  // evaluator's GL_TIMESTAMP pair, which llvmpipe underestimates for single draws.
  Spread wall_ms;
  Spread gpu_ms;
  int runs = 0;  // frames (of the timed ones) on which process() ran
  // Its function ran inside the pass of the node reading it (pointwise fusion): its time is in
  // that node's.
  bool fused = false;
};

struct PipelineTiming {
  bool static_cached = false;    // the mode: static nodes' outputs kept for the next frame
  std::vector<NodeStats> nodes;  // in evaluation order
  // Wall time of evaluate() + glFinish with node timing switched off (timer queries make the
  // CPU wait for each node, which would inflate the frame).
  Spread frame_ms;
  Spread node_wall_sum_ms;  // per frame, the sum of the nodes' synced wall times
};

struct TimingPlan {
  int frames = 5;  // timed frames
  int warmup = 2;  // untimed frames first: shader compilation, first allocations
};

struct PipelineTimings {
  // Outputs released after their last reader, static ones included: every node runs every frame.
  PipelineTiming every_node_runs;
  // Outputs released after their last reader except those of static nodes (nothing upstream
  // depends on time), reused on the next frame: what `aquarelle render` does.
  PipelineTiming cached;
  // Copy-pass batches run between the frames, so the yardstick is sampled over the same
  // period as the frames (the machine's load changes during a run).
  std::vector<CopyPass::Sample> copy_samples;
};

// Evaluates frames first_frame, first_frame+1, ... (time-dependent nodes see time advance) in
// both modes, frame by frame alternately so that neither mode gets a quieter machine.
Result<PipelineTimings> time_pipeline(GlContext& context, const Registry& registry,
                                      const Graph& graph, const TimingPlan& plan,
                                      CopyPass& copy_pass);

// `bench --baseline`: a graph's frame and a baseline graph's, timed alternately frame by frame
// in one process (static nodes' outputs kept, as `aquarelle render` runs), so both see the same
// machine: on a shared host the ratio of two separate runs moves with the load between them.
struct SideBySide {
  Spread graph_ms;     // the graph's frames
  Spread baseline_ms;  // the baseline's frames
  Spread pair_ratio;   // per pair of frames (the same frame number): graph / baseline
};
Result<SideBySide> time_side_by_side(GlContext& context, const Registry& registry,
                                     const Graph& graph, const Graph& baseline,
                                     const TimingPlan& plan);

// Wall time of evaluate() + glFinish over `frames` frames after `warmup`, static nodes' outputs
// kept between frames (as `aquarelle render` runs); the warm-up frame's output is read back to
// `first`.
struct FrameRun {
  Spread frame_ms;
  ImageF first;  // output at graph.settings.first_frame
};
Result<FrameRun> run_frames(Evaluator& evaluator, const Graph& graph, int frames, int warmup);

}  // namespace aq::app
