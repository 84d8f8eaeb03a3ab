// Times a full-screen copy pass with GL timestamp queries (see bench_copy_pass.h). The GL is
// written out here rather than borrowed from the evaluator so that the yardstick is exactly
// one draw with one texture read per pixel and nothing else.
#include "bench_copy_pass.h"

#include <aquarelle/core/gl_objects.h>
#include <aquarelle/plugin.h>

#include <chrono>
#include <string>
#include <utility>
#include <vector>

namespace aq::app {

namespace {

constexpr int kCopiesPerSample = 4;

constexpr const char* kVertexShader = R"(#version 450 core
out vec2 v_uv;
void main() {
  // One triangle covering the viewport: (-1,-1), (3,-1), (-1,3).
  vec2 corner = vec2(float((gl_VertexID & 1) << 2), float((gl_VertexID & 2) << 1)) - 1.0;
  v_uv = corner * 0.5 + 0.5;
  gl_Position = vec4(corner, 0.0, 1.0);
}
)";

constexpr const char* kFragmentShader = R"(#version 450 core
in vec2 v_uv;
layout(binding = 0) uniform sampler2D u_image;
layout(location = 0) out vec4 o_color;
void main() { o_color = texture(u_image, v_uv); }
)";

Result<gl::Shader> compile(GLenum stage, const char* source) {
  gl::Shader shader(glCreateShader(stage));
  glShaderSource(shader.get(), 1, &source, nullptr);
  glCompileShader(shader.get());
  GLint ok = GL_FALSE;
  glGetShaderiv(shader.get(), GL_COMPILE_STATUS, &ok);
  if (ok != GL_TRUE) {
    char log[2048] = {};
    glGetShaderInfoLog(shader.get(), sizeof(log), nullptr, log);
    return make_error(std::string("copy pass shader did not compile: ") + log);
  }
  return shader;
}

Result<gl::Program> link_copy_program() {
  auto vertex = compile(GL_VERTEX_SHADER, kVertexShader);
  if (!vertex.ok()) return vertex.error();
  auto fragment = compile(GL_FRAGMENT_SHADER, kFragmentShader);
  if (!fragment.ok()) return fragment.error();
  gl::Program program(glCreateProgram());
  glAttachShader(program.get(), vertex->get());
  glAttachShader(program.get(), fragment->get());
  glLinkProgram(program.get());
  GLint ok = GL_FALSE;
  glGetProgramiv(program.get(), GL_LINK_STATUS, &ok);
  if (ok != GL_TRUE) {
    char log[2048] = {};
    glGetProgramInfoLog(program.get(), sizeof(log), nullptr, log);
    return make_error(std::string("copy pass program did not link: ") + log);
  }
  return program;
}

// A texture set up as the pool makes them: clamp-to-edge, linear filtering.
gl::Texture make_image_texture(int width, int height, GLenum internal_format) {
  gl::Texture texture = gl::make_texture();
  glBindTexture(GL_TEXTURE_2D, texture.get());
  glTexStorage2D(GL_TEXTURE_2D, 1, internal_format, width, height);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
  glBindTexture(GL_TEXTURE_2D, 0);
  return texture;
}

}  // namespace

Result<CopyPass> CopyPass::create(int width, int height, uint32_t format) {
  if (format != AQ_FORMAT_RGBA16F && format != AQ_FORMAT_RGBA32F) {
    return make_error("copy pass: format must be RGBA16F or RGBA32F");
  }
  const GLenum internal_format = format == AQ_FORMAT_RGBA32F ? GL_RGBA32F : GL_RGBA16F;
  auto program = link_copy_program();
  if (!program.ok()) return program.error();
  CopyPass pass;
  pass.width_ = width;
  pass.height_ = height;
  pass.program_ = std::move(*program);
  pass.source_ = make_image_texture(width, height, internal_format);
  pass.target_ = make_image_texture(width, height, internal_format);
  // Defined contents, so the copy reads numbers rather than whatever memory held.
  std::vector<float> pixels(static_cast<size_t>(width) * height * 4);
  for (size_t i = 0; i < pixels.size(); ++i) pixels[i] = static_cast<float>(i % 251) / 250.0f;
  glBindTexture(GL_TEXTURE_2D, pass.source_.get());
  glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
  glTexSubImage2D(GL_TEXTURE_2D, 0, 0, 0, width, height, GL_RGBA, GL_FLOAT, pixels.data());
  glBindTexture(GL_TEXTURE_2D, 0);

  pass.into_target_ = gl::make_framebuffer();
  pass.into_source_ = gl::make_framebuffer();
  bool complete = true;
  for (auto [framebuffer, texture] : {std::pair{pass.into_target_.get(), pass.target_.get()},
                                      std::pair{pass.into_source_.get(), pass.source_.get()}}) {
    glBindFramebuffer(GL_FRAMEBUFFER, framebuffer);
    glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, texture, 0);
    complete = complete && glCheckFramebufferStatus(GL_FRAMEBUFFER) == GL_FRAMEBUFFER_COMPLETE;
  }
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
  if (!complete) return make_error("copy pass: a target framebuffer is incomplete");
  pass.vertex_array_ = gl::make_vertex_array();
  pass.start_ = gl::make_query();
  pass.end_ = gl::make_query();
  return pass;
}

CopyPass::Sample CopyPass::run_batch() {
  // Each sample is a batch of copies between two glFinish calls, divided by the batch size:
  // the sync cost is shared, and the copies are rasterised as they would be in a pipeline.
  // The copies ping-pong between two textures so that each reads the one before: repeated
  // opaque full-screen draws into one target would let llvmpipe drop all but the last (it
  // discards a tile's earlier commands when an opaque triangle covers the whole tile), which
  // made the yardstick read four times too fast.
  glViewport(0, 0, width_, height_);
  glDisable(GL_BLEND);
  glDisable(GL_DEPTH_TEST);
  glDisable(GL_SCISSOR_TEST);
  glUseProgram(program_.get());
  glBindVertexArray(vertex_array_.get());
  glActiveTexture(GL_TEXTURE0);
  glFinish();

  auto wall_start = std::chrono::steady_clock::now();
  glQueryCounter(start_.get(), GL_TIMESTAMP);
  for (int k = 0; k < kCopiesPerSample; ++k) {
    const bool even = k % 2 == 0;
    glBindFramebuffer(GL_FRAMEBUFFER, even ? into_target_.get() : into_source_.get());
    glBindTexture(GL_TEXTURE_2D, even ? source_.get() : target_.get());
    glDrawArrays(GL_TRIANGLES, 0, 3);
  }
  glQueryCounter(end_.get(), GL_TIMESTAMP);
  glFinish();
  auto wall_end = std::chrono::steady_clock::now();
  GLuint64 begin_ns = 0, end_ns = 0;
  glGetQueryObjectui64v(start_.get(), GL_QUERY_RESULT, &begin_ns);
  glGetQueryObjectui64v(end_.get(), GL_QUERY_RESULT, &end_ns);

  glBindTexture(GL_TEXTURE_2D, 0);
  glBindVertexArray(0);
  glUseProgram(0);
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
  Sample sample;
  sample.wall_ms =
      std::chrono::duration<double, std::milli>(wall_end - wall_start).count() / kCopiesPerSample;
  sample.timestamp_ms =
      end_ns > begin_ns ? static_cast<double>(end_ns - begin_ns) * 1e-6 / kCopiesPerSample : 0.0;
  return sample;
}

}  // namespace aq::app
