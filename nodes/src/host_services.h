// The host services a plugin calls during process() (the aq_host table of plugin.h): shader
// programs, output and scratch textures from the pool, pass-through, scene outputs, render
// targets, the full-screen triangle, errors and logging. Each call acts on the node being
// processed, which the evaluator names in a CallState handed to the plugin as host_data.
#pragma once

#include <aquarelle/core/gl_objects.h>
#include <aquarelle/core/registry.h>
#include <aquarelle/core/texture_pool.h>
#include <aquarelle/plugin.h>

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
  gl::Query timer_start;  // GL_TIMESTAMP pairs: llvmpipe's GL_TIME_ELAPSED reads garbage when
  gl::Query timer_end;    // a query spans shader compilation, timestamps do not
  BuiltinState builtin;

  // GL_TIMESTAMP pair around this node's work.
  void mark_start();
  void mark_end();
  double marked_gpu_ms() const;
};

class HostServices;

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
  uint32_t working_format = AQ_FORMAT_RGBA16F;

  // Epilogue fusion (AQ_NODE_EPILOGUE): the pointwise stages the node's draws into output 0
  // apply (null: none, the identity), and how many draws applied them.
  const std::vector<FusedStage>* epilogue = nullptr;
  int epilogue_draws = 0;

  // Per output: output_image handed out the texture this instance's output had before, with
  // its content (aq_host::output_kept).
  std::vector<bool> kept_outputs;

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

  GlContext& context_;
  TexturePool& pool_;
  ShaderCache shaders_;
  gl::VertexArray empty_vao_;
  gl::Framebuffer framebuffer_;
  GLuint attached_colors_ = 0;
  aq_host host_{};
};

// Records a host error for the call (as host->fail does).
void fail_call(CallState& call, const std::string& message);

}  // namespace aq
