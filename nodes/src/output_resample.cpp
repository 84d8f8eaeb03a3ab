// The proxy output upscale (see output_resample.h).
#include "output_resample.h"

namespace aq {

namespace {

// Pixel centres map to pixel centres (v_uv spans the target), so the image neither shifts nor
// shrinks; the sampler's clamp-to-edge handles the border.
constexpr const char* kResampleFragment = R"(
in vec2 v_uv;
layout(location = 0) out vec4 o_color;
uniform sampler2D u_image;
void main() { o_color = texture(u_image, v_uv); }
)";
const aq_shader_source kResampleSource = {"output_resample.frag", kResampleFragment, nullptr};

bool filterable(uint32_t format) {
  return format == AQ_FORMAT_RGBA16F || format == AQ_FORMAT_RGBA32F || format == AQ_FORMAT_R32F;
}

}  // namespace

Result<TextureRef> OutputResampler::resample(ShaderCache& shaders, TexturePool& pool,
                                             const TextureRef& source, int width, int height) {
  const aq_image& in = source->image;
  if ((in.width == width && in.height == height) || !filterable(in.format)) return source;
  auto program = shaders.program(nullptr, &kResampleSource);
  if (!program.ok()) return program.error();
  if (!framebuffer_) {
    GLuint name = 0;
    glCreateFramebuffers(1, &name);  // created, not just named: the DSA calls below need that
    framebuffer_ = gl::Framebuffer(name);
    vertex_array_ = gl::make_vertex_array();
  }
  TextureRef out = pool.acquire(width, height, in.format);
  glNamedFramebufferTexture(framebuffer_.get(), GL_COLOR_ATTACHMENT0, out->image.texture, 0);
  glBindFramebuffer(GL_FRAMEBUFFER, framebuffer_.get());
  glViewport(0, 0, width, height);
  glUseProgram(*program);
  glBindTextureUnit(0, in.texture);
  glUniform1i(glGetUniformLocation(*program, "u_image"), 0);
  glBindVertexArray(vertex_array_.get());
  glDrawArrays(GL_TRIANGLES, 0, 3);
  glBindVertexArray(0);
  glBindTextureUnit(0, 0);
  glUseProgram(0);
  glNamedFramebufferTexture(framebuffer_.get(), GL_COLOR_ATTACHMENT0, 0, 0);
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
  return out;
}

}  // namespace aq
