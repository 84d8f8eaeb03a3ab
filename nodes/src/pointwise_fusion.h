// Fused pointwise passes: a chain of pointwise nodes that give their per-pixel function
// (aq_pointwise_desc) runs as one shader instead of one pass per node, optionally resampling
// its input to another size on the way (the output upscale of a proxy render), as Blender's
// compositor fuses its pixel operations.
#pragma once

#include <aquarelle/core/gl_objects.h>
#include <aquarelle/core/result.h>
#include <aquarelle/core/texture_pool.h>
#include <aquarelle/plugin.h>

#include <string>
#include <vector>

#include "shader_cache.h"

namespace aq {

struct FusedStage {
  const aq_pointwise_desc* pointwise = nullptr;
  void* instance = nullptr;
  aq_process_ctx* ctx = nullptr;  // as for process(); its width and height are the pass's
  // The node's inputs after the first: port name and texture, bound as AQ_UNIFORM(name).
  std::vector<std::pair<std::string, GLuint>> samplers;
};

// Texture units the host binds fused stages' extra inputs to: above those plugins use.
constexpr GLuint kFusedSamplerUnit = 20;

class PointwiseFuser {
 public:
  // Applies `stages` in order to `input`, writing a new pool texture of width x height in
  // `format` (AQ_FORMAT_RGBA8_HDR: encoded, aquarelle/hdr8.glsl). An input of another size is read
  // with bilinear filtering (pixel centres map to pixel centres), one of the same size texel by
  // texel.
  Result<TextureRef> run(ShaderCache& shaders, TexturePool& pool,
                         const std::vector<FusedStage>& stages, const TextureRef& input, int width,
                         int height, uint32_t format);

 private:
  gl::Framebuffer framebuffer_;
  gl::VertexArray vertex_array_;
};

// The fused fragment shader for functions `glsl` (stage i's uniforms get the prefix
// "aq_s<i>_"), reading its input by texel or, with `resample`, bilinearly, and decoding it when
// it is AQ_FORMAT_RGBA8_HDR (with no stage: the host's decode of an encoded image), and encoding
// what it writes with `encode_hdr8`.
std::string fused_fragment_source(const std::vector<const char*>& glsl, bool resample,
                                  bool decode_hdr8 = false, bool encode_hdr8 = false);
std::string fused_uniform_prefix(size_t stage);

// What the host prepends to the fragment shaders of an AQ_NODE_EPILOGUE node: `vec4
// aq_epilogue_at(vec4, vec2 pixel)`, the identity without stages, else the stages applied in
// order at the pixel centre `pixel` of an image of `aq_epilogue_size` pixels (stage i's uniforms
// prefixed as in a fused pass), and `vec4 aq_epilogue(vec4)`, the same at gl_FragCoord.
std::string epilogue_source(const std::vector<FusedStage>* stages);
// Sets the stages' uniforms and aq_epilogue_size on `program` for a draw of width x height;
// false when a stage's set_uniforms failed.
bool set_epilogue_uniforms(const std::vector<FusedStage>& stages, GLuint program, int width,
                           int height);
// Unbinds what set_epilogue_uniforms (or a fused pass) bound for the stages' extra inputs.
void unbind_stage_samplers(const std::vector<FusedStage>& stages);

}  // namespace aq
