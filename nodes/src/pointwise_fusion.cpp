// Fused pointwise passes (see pointwise_fusion.h).
#include "pointwise_fusion.h"

namespace aq {

std::string fused_uniform_prefix(size_t stage) {
  return "aq_s" + std::to_string(stage) + "_";
}

namespace {
// The stages' functions, stage i's named `function`<i> with its uniforms prefixed
// (fused_uniform_prefix), and the calls that apply them in order to `c` at the pixel centre
// `pixel` of an image of `size` pixels: what a fused pass and an epilogue both put in their
// shader.
struct StageCode {
  std::string functions;
  std::string calls;
};
StageCode stage_code(const std::vector<const char*>& glsl, const std::string& function,
                     const char* pixel, const char* size) {
  StageCode code;
  for (size_t i = 0; i < glsl.size(); ++i) {
    const std::string name = function + std::to_string(i);
    code.functions += "#define AQ_APPLY " + name + "\n";
    code.functions += "#define AQ_UNIFORM(name) " + fused_uniform_prefix(i) + "##name\n";
    code.functions += glsl[i];
    code.functions += "\n#undef AQ_APPLY\n#undef AQ_UNIFORM\n";
    code.calls += "  c = " + name + "(c, " + pixel + ", " + size + ");\n";
  }
  return code;
}
}  // namespace

std::string fused_fragment_source(const std::vector<const char*>& glsl, bool resample,
                                  bool decode_hdr8, bool encode_hdr8) {
  const StageCode code = stage_code(glsl, "aq_apply_", "gl_FragCoord.xy", "aq_fused_size");
  std::string source = decode_hdr8 || encode_hdr8 ? "#include \"aquarelle/hdr8.glsl\"\n" : "";
  source += code.functions;
  source +=
      "in vec2 v_uv;\n"
      "layout(location = 0) out vec4 o_color;\n"
      "uniform sampler2D aq_fused_input;\n"
      "uniform vec2 aq_fused_size;\n"
      "void main() {\n";
  source += resample ? "  vec4 c = texture(aq_fused_input, v_uv);\n"
                     : "  vec4 c = texelFetch(aq_fused_input, ivec2(gl_FragCoord.xy), 0);\n";
  if (decode_hdr8) source += "  c = aq_hdr8_decode(c);\n";
  source += code.calls;
  source += encode_hdr8 ? "  o_color = aq_hdr8_encode(c);\n}\n" : "  o_color = c;\n}\n";
  return source;
}

std::string epilogue_source(const std::vector<FusedStage>* stages) {
  // aq_epilogue_at applies the chain at any pixel, for a shader that writes several pixels per
  // fragment (2 x 2 blocks); aq_epilogue at the fragment's own.
  const std::string at_fragment =
      "vec4 aq_epilogue(vec4 c) { return aq_epilogue_at(c, gl_FragCoord.xy); }\n";
  if (stages == nullptr || stages->empty())
    return "vec4 aq_epilogue_at(vec4 c, vec2 pixel) { return c; }\n" + at_fragment;
  std::vector<const char*> glsl;
  for (const FusedStage& stage : *stages) glsl.push_back(stage.pointwise->glsl);
  const StageCode code = stage_code(glsl, "aq_epilogue_", "pixel", "aq_epilogue_size");
  return code.functions +
         "uniform vec2 aq_epilogue_size;\nvec4 aq_epilogue_at(vec4 c, vec2 pixel) {\n" +
         code.calls + "  return c;\n}\n" + at_fragment;
}

namespace {
// Binds every stage's extra inputs to units from kFusedSamplerUnit on (program bound).
void bind_stage_samplers(const std::vector<FusedStage>& stages, GLuint program) {
  GLuint unit = kFusedSamplerUnit;
  for (size_t i = 0; i < stages.size(); ++i) {
    for (const auto& [name, texture] : stages[i].samplers) {
      glBindTextureUnit(unit, texture);
      glUniform1i(glGetUniformLocation(program, (fused_uniform_prefix(i) + name).c_str()),
                  static_cast<GLint>(unit));
      ++unit;
    }
  }
}
}  // namespace

void unbind_stage_samplers(const std::vector<FusedStage>& stages) {
  GLuint unit = kFusedSamplerUnit;
  for (const FusedStage& stage : stages)
    for (size_t k = 0; k < stage.samplers.size(); ++k) glBindTextureUnit(unit++, 0);
}

namespace {
// Binds the stages' extra inputs and sets their uniforms on `program` (bound) for a draw of
// width x height, then sets `size_uniform`. Returns the 1-based index of a stage whose
// set_uniforms failed, 0 when all succeeded.
size_t set_stage_uniforms(const std::vector<FusedStage>& stages, GLuint program, int width,
                          int height, const char* size_uniform) {
  bind_stage_samplers(stages, program);
  for (size_t i = 0; i < stages.size(); ++i) {
    const FusedStage& stage = stages[i];
    stage.ctx->width = width;
    stage.ctx->height = height;
    const std::string prefix = fused_uniform_prefix(i);
    if (stage.pointwise->set_uniforms(stage.instance, stage.ctx, program, prefix.c_str()) != AQ_OK)
      return i + 1;
  }
  glUseProgram(program);  // a stage may have changed the binding
  glUniform2f(glGetUniformLocation(program, size_uniform), static_cast<float>(width),
              static_cast<float>(height));
  return 0;
}
}  // namespace

bool set_epilogue_uniforms(const std::vector<FusedStage>& stages, GLuint program, int width,
                           int height) {
  return set_stage_uniforms(stages, program, width, height, "aq_epilogue_size") == 0;
}

Result<TextureRef> PointwiseFuser::run(ShaderCache& shaders, TexturePool& pool,
                                       const std::vector<FusedStage>& stages,
                                       const TextureRef& input, int width, int height,
                                       uint32_t format) {
  const aq_image& in = input->image;
  const bool resample = in.width != width || in.height != height;
  std::vector<const char*> glsl;
  std::string names;
  for (const FusedStage& stage : stages) {
    glsl.push_back(stage.pointwise->glsl);
    names += (names.empty() ? "" : "+") +
             std::string(stage.pointwise->name != nullptr ? stage.pointwise->name : "pointwise");
  }
  const std::string text = fused_fragment_source(glsl, resample, in.format == AQ_FORMAT_RGBA8_HDR,
                                                 format == AQ_FORMAT_RGBA8_HDR);
  const std::string name = "fused(" + names + ")";
  const aq_shader_source fragment{name.c_str(), text.c_str(), nullptr};
  auto program = shaders.program(nullptr, &fragment);
  if (!program.ok()) return program.error();
  if (!framebuffer_) {
    GLuint framebuffer = 0;
    glCreateFramebuffers(1, &framebuffer);  // created, not just named: DSA calls need that
    framebuffer_ = gl::Framebuffer(framebuffer);
    vertex_array_ = gl::make_vertex_array();
  }
  TextureRef out = pool.acquire(width, height, format);
  glUseProgram(*program);
  if (const size_t failed = set_stage_uniforms(stages, *program, width, height, "aq_fused_size")) {
    unbind_stage_samplers(stages);
    glUseProgram(0);
    return make_error("setting the uniforms of fused stage " + std::to_string(failed) + " failed");
  }
  glBindTextureUnit(0, in.texture);
  glUniform1i(glGetUniformLocation(*program, "aq_fused_input"), 0);
  glNamedFramebufferTexture(framebuffer_.get(), GL_COLOR_ATTACHMENT0, out->image.texture, 0);
  glBindFramebuffer(GL_FRAMEBUFFER, framebuffer_.get());
  glViewport(0, 0, width, height);
  glBindVertexArray(vertex_array_.get());
  glDrawArrays(GL_TRIANGLES, 0, 3);
  glBindVertexArray(0);
  unbind_stage_samplers(stages);
  glBindTextureUnit(0, 0);
  glUseProgram(0);
  glNamedFramebufferTexture(framebuffer_.get(), GL_COLOR_ATTACHMENT0, 0, 0);
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
  return out;
}

}  // namespace aq
