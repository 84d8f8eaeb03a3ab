// The host services a plugin calls during process() (the aq_host table of plugin.h): shader
// programs, output and scratch textures from the pool, pass-through, scene outputs, render
// targets, the full-screen triangle, errors and logging. Each call acts on the node being
// processed, which the evaluator names in a CallState handed to the plugin as host_data.
#pragma once

#include <aquarelle/core/gl_objects.h>
#include <aquarelle/core/registry.h>
#include <aquarelle/core/texture_pool.h>
#include <aquarelle/plugin.h>
#include <aquarelle/sdk/region.hpp>

#include <optional>
#include <string>
#include <vector>

#include "builtin_nodes.h"
#include "pointwise_fusion.h"
#include "shader_cache.h"

namespace aq {

class GlContext;

// What the evaluator keeps per node between evaluations.
struct NodeState {
  const NodeType* type = nullptr;
  void* instance = nullptr;
  uint64_t key = 0;
  bool valid = false;  // outputs hold the result for `key`
  // Nonzero once the node instance asked whether its outputs were kept (aq_host::output_kept):
  // from then on its outputs are acquired with this tag (unique to the instance, never reused),
  // so that it gets them back; untagged otherwise, so that other nodes' textures stay free.
  uint64_t writer_tag = 0;
  std::vector<TextureRef> images;
  std::vector<const aq_scene*> scenes;

  // Damage tracking (aq_host::input_damage). What the node saw on its last successful call: its
  // own key (CallState::self_key) and its inputs' keys.
  bool seen = false;
  uint64_t seen_self_key = 0;
  uint64_t seen_damage_key = 0;  // CallState::damage_key
  std::vector<uint64_t> seen_input_keys;
  // Where each output changed on that call, from what it held under `previous_key` (the key
  // before the call); all() where the node said nothing (aq_host::set_output_damage).
  uint64_t previous_key = 0;
  std::vector<Region> output_damage;
  // Per output, where it may hold anything but its background (aq_host::set_output_bounds).
  std::vector<Region> output_bounds;
  // Per output, the 1D pass its writer left to its reader (aq_host::defer_axis), if any.
  std::vector<std::optional<aq_axis_pass>> output_deferred;
  // Share of the outputs' pixels that call redrew (1 when it said nothing; -1 without image
  // outputs), for --stats.
  double redrawn = 1.0;

  gl::Query timer_start;  // GL_TIMESTAMP pairs: llvmpipe's GL_TIME_ELAPSED reads garbage when
  gl::Query timer_end;    // a query spans shader compilation, timestamps do not
  BuiltinState builtin;

  // GL_TIMESTAMP pair around this node's work.
  void mark_start();
  void mark_end();
  double marked_gpu_ms() const;
};

class HostServices;

// The output that feeds an input, for the damage an input saw (null state: a list of links or
// nothing connected).
struct DamageSource {
  const NodeState* state = nullptr;
  uint32_t output = 0;
  std::string port;
};

// One node's call into the host: passed to the plugin as aq_process_ctx::host_data.
struct CallState {
  HostServices* host = nullptr;
  NodeState* state = nullptr;
  std::string node_id;
  std::string error;
  std::vector<TextureRef> scratch;
  const std::vector<TextureRef>* input_refs = nullptr;
  // Per output: the format the plan stores it in (PlannedNode::stored_formats, 0: the
  // plugin's choice); null or empty: none changes.
  const std::vector<uint32_t>* stored_formats = nullptr;
  // Per output: the plan lets it leave its last 1D pass to its reader
  // (PlannedNode::axis_deferrable); null or empty: none may.
  const std::vector<bool>* axis_deferrable = nullptr;
  // Per output: something reads it in this evaluation (PlannedNode::outputs_read); null or
  // empty: every output counts as read.
  const std::vector<bool>* outputs_read = nullptr;
  uint32_t working_format = AQ_FORMAT_RGBA16F;

  // Epilogue fusion (AQ_NODE_EPILOGUE): the pointwise stages the node's draws into output 0
  // apply (null: none, the identity), and how many draws applied them.
  const std::vector<FusedStage>* epilogue = nullptr;
  int epilogue_draws = 0;

  // Per output: output_image handed out the texture this instance's output had before, with
  // its content (aq_host::output_kept).
  std::vector<bool> kept_outputs;
  // Per output: output_image handed it out in this call (not a pass-through of an input).
  std::vector<bool> acquired_outputs;

  // Damage tracking: per input its source and key now; the node's own key now (its cache key
  // without the inputs: type, parameters, connections, size, format, quality, the frame when
  // time-dependent, and for an epilogue producer the nodes fused into its draw).
  const std::vector<DamageSource>* sources = nullptr;
  const std::vector<uint64_t>* input_keys = nullptr;
  uint64_t self_key = 0;
  // The same without the frame: what input_damage compares, so that a time-dependent node
  // learns where its inputs changed (and adds what time changes itself).
  uint64_t damage_key = 0;
  // With an epilogue: what its stages' other inputs or parameters changed (evaluator).
  Region epilogue_damage;
  // draw_fullscreen's rects (aq_host::set_draw_region) and what set_output_damage declared.
  Region draw_region = Region::everything();
  std::vector<std::optional<Region>> declared_damage;
  std::vector<std::optional<Region>> declared_bounds;
  std::vector<std::optional<aq_axis_pass>> declared_deferral;  // aq_host::defer_axis

  uint32_t stored_format(uint32_t index) const {
    return stored_formats != nullptr && index < stored_formats->size() ? (*stored_formats)[index]
                                                                       : 0;
  }
};

class HostServices {
 public:
  HostServices(GlContext& context, TexturePool& pool);
  HostServices(const HostServices&) = delete;
  HostServices& operator=(const HostServices&) = delete;

  const aq_host* table() const { return &host_; }
  ShaderCache& shaders() { return shaders_; }
  TexturePool& pool() { return pool_; }
  // Plugins look GL functions up through the evaluator that is evaluating now.
  void make_current() { current_ = this; }
  // Leaves GL as the next node expects to find it, whatever this node left bound.
  static void reset_gl_state();

 private:
  static HostServices* current_;
  static void* get_proc_address(const char* name);
  static bool apply_epilogue(CallState* call);
  static void fail(void* data, const char* message);
  static void log(void* data, int level, const char* message);
  static uint32_t program(void* data, const aq_shader_source* vertex,
                          const aq_shader_source* fragment);
  static bool valid_format(CallState* call, const char* function, uint32_t format);
  static bool valid_size(CallState* call, int32_t width, int32_t height);
  static int output_image(void* data, uint32_t index, int32_t width, int32_t height,
                          uint32_t format, aq_image* out);
  static int pass_through(void* data, uint32_t index, uint32_t input_index);
  static int output_kept(void* data, uint32_t index);
  static int output_scene(void* data, uint32_t index, const aq_scene* scene);
  static int scratch_image(void* data, int32_t width, int32_t height, uint32_t format,
                           aq_image* out);
  static int bind_targets(void* data, const aq_image* colors, uint32_t count,
                          const aq_image* depth);
  static void draw_fullscreen(void* data);
  void draw_rects(const std::vector<PixelRect>& rects);
  size_t viewport_batch();
  static int input_damage(void* data, uint32_t index, aq_rect* rects, uint32_t capacity);
  static int epilogue_damage(void* data, aq_rect* rects, uint32_t capacity);
  static int set_output_damage(void* data, uint32_t index, const aq_rect* rects, uint32_t count);
  static void set_draw_region(void* data, const aq_rect* rects, uint32_t count);
  static int set_output_bounds(void* data, uint32_t index, const aq_rect* rects, uint32_t count);
  static int input_bounds(void* data, uint32_t index, aq_rect* rects, uint32_t capacity);
  static int may_defer_axis(void* data, uint32_t index);
  static int defer_axis(void* data, uint32_t index, const aq_axis_pass* pass);
  static int input_deferred_axis(void* data, uint32_t index, aq_axis_pass* pass);
  static int output_read(void* data, uint32_t index);

  GlContext& context_;
  TexturePool& pool_;
  ShaderCache shaders_;
  gl::VertexArray empty_vao_;
  size_t viewport_batch_ = 0;  // 0: not asked yet (viewport_batch)
  gl::Framebuffer framebuffer_;
  GLuint attached_colors_ = 0;
  aq_host host_{};
};

// The pool writer tag of a node's output (TexturePool::acquire), 0 until it asked output_kept.
uint64_t output_writer(const NodeState& state, uint32_t index);

// Records a host error for the call (as host->fail does).
void fail_call(CallState& call, const std::string& message);

// Where input `index` of the call's node may differ from what it held on the node's last
// successful call (aq_host::input_damage): all() when not known.
Region input_damage_of(const CallState& call, uint32_t index);

// Before a call: nothing declared, the whole target drawn. After a successful one: what the node
// saw, where its outputs changed (`previous_key`: the node's key before the call) and which 1D
// passes it left to its readers.
void begin_damage_call(CallState& call, size_t output_count);
void finish_damage_call(NodeState& state, const CallState& call, uint64_t previous_key);
// Where each output changed from what it held under `previous_key` (unset: everywhere) and its
// bounds (unset: everywhere), nothing left to the readers; finish_damage_call's second half,
// alone for a fused chain's result.
void record_output_damage(NodeState& state, uint64_t previous_key,
                          const std::vector<std::optional<Region>>& damage,
                          const std::vector<std::optional<Region>>& bounds);

}  // namespace aq
