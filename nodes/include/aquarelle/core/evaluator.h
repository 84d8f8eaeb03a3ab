// Evaluates a graph for one frame by pulling from the requested output.
//
//   compile: the plan (plan.h): cull to the nodes the output depends on, sort them, count
//            readers per output, mark static nodes, choose fused chains, size each pass
//   execute: for each node, compute its cache key = hash(type, params, input keys, settings,
//            time if time-dependent); equal to last run → reuse its outputs, else process()
//   release: after a node's last reader ran, its outputs go back to the texture pool unless
//            the cache keeps them (retain_outputs)
//
// Every process() is timed with GPU timer queries and CPU wall time.
#pragma once

#include <aquarelle/core/gl_context.h>
#include <aquarelle/core/graph.h>
#include <aquarelle/core/image.h>
#include <aquarelle/core/plan.h>
#include <aquarelle/core/registry.h>
#include <aquarelle/core/result.h>
#include <aquarelle/core/texture_pool.h>

#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <string>
#include <vector>

namespace aq {

struct NodeTiming {
  std::string node;
  std::string type;
  double gpu_ms = 0;    // GPU time of process() (timer query)
  double cpu_ms = 0;    // wall time of process()
  bool cached = false;  // reused from the previous evaluation, not run
  bool fused = false;   // ran inside the pass of the node reading it (pointwise fusion)
  // Share of its outputs' pixels the run redrew: below 1 when the node redrew only what changed
  // (damage tracking, aq_host::set_output_damage); negative for a node without image outputs.
  double redrawn = 1.0;
};

struct EvalOptions {
  int frame = 1;
  // Keep every node's outputs between evaluations so unchanged nodes are not re-run (editor,
  // animation with static parts). Off: outputs return to the pool after their last reader.
  bool retain_outputs = true;
  // With retain_outputs off: still keep the outputs of static nodes (nothing upstream depends
  // on time), which the next frame reuses. Memory then stays bounded by the graph's width plus
  // its static results; turn off to bound it by the width alone.
  bool retain_static_outputs = true;
  bool measure_gpu_time = true;
  // Wait for the GPU (glFinish) before and after each node's process(), so cpu_ms covers the
  // node's GPU work as well: `aquarelle bench` uses it because llvmpipe's GL_TIMESTAMP pairs
  // around draws that no flush separates read far too low. Slower; off by default.
  bool finish_each_node = false;
  // Run chains of pointwise nodes that give a fusable function as one pass (and the output's
  // pointwise tail inside the proxy upscale). Off: every node runs its own process().
  bool fuse_pointwise = true;
  // Store outputs in the narrower format their readers need: RGBA8 for AQ_PORT_8BIT_ENOUGH
  // readers, RGBA8_HDR where writer and readers say AQ_PORT_HDR8 (plan.h). The environment
  // variables AQUARELLE_FORMATS_BY_NEED=0 (both) and AQUARELLE_HDR8=0 (the second) turn it off;
  // AQUARELLE_MORPH_BLOCKS=0 only RGBA8_HDR_BLOCKS between AQ_PORT_BLOCKS ports, and
  // AQUARELLE_DEFER_AXIS=0 the 1D passes handed between AQ_PORT_DEFER_AXIS nodes.
  bool formats_by_need = true;
  // Images for `image_input` nodes, by their `name` parameter (tests, embedding).
  const std::map<std::string, ImageF>* images = nullptr;
};

// Reads a texture of the current context back as float pixels (RGBA, or 1 channel for R32F,
// depth and ids).
// Reads in bands of rows of at most `max_bytes_per_read` bytes each (a GL read's size is a
// GLsizei, so one read of a 16384x16384 RGBA float image would overflow it).
inline constexpr int64_t kMaxReadbackBytes = int64_t{1} << 30;
Result<ImageF> read_texture(GLuint texture, int width, int height, uint32_t format,
                            int64_t max_bytes_per_read = kMaxReadbackBytes);
// Rows per band for a width and pixel size (at least 1).
int readback_rows_per_band(int width, int bytes_per_pixel, int64_t max_bytes);

class Evaluator {
 public:
  Evaluator(GlContext& context, const Registry& registry);
  ~Evaluator();
  Evaluator(const Evaluator&) = delete;
  Evaluator& operator=(const Evaluator&) = delete;

  // Evaluates `output` (or graph.output) for options.frame. The result stays valid until the
  // next evaluate() or until released. Errors name the node, e.g. "node 'blur' (blur): ...".
  Result<TextureRef> evaluate(const Graph& graph, const EvalOptions& options,
                              const std::optional<PortRef>& output = std::nullopt);

  // The plan evaluate() would execute for these options (nothing runs, no GL needed).
  Result<Plan> plan(const Graph& graph, const EvalOptions& options,
                    const std::optional<PortRef>& output = std::nullopt) const;

  // Reads a texture back as float pixels (RGBA, or 1 channel for R32F).
  Result<ImageF> read_back(const TextureRef& texture);

  const std::vector<NodeTiming>& last_timings() const { return timings_; }
  // How many times each node id has been processed (not reused) since construction.
  const std::map<std::string, int>& run_counts() const { return run_counts_; }
  TexturePool& pool() { return *pool_; }
  // Drops cached outputs and node instances (e.g. after the plugin set or context changed).
  void clear();
  // Hot reload: shaders are read from their source path when it exists.
  void set_shader_hot_reload(bool enabled);

  struct Impl;

 private:
  GlContext& context_;
  const Registry& registry_;
  std::unique_ptr<TexturePool> pool_;
  std::unique_ptr<Impl> impl_;
  std::vector<NodeTiming> timings_;
  std::map<std::string, int> run_counts_;
};

}  // namespace aq
