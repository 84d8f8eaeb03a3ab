// RAII owners for GL objects. Each deletes its object when destroyed (with the context that
// made it current), so nothing leaks across frames; all are move-only.
#pragma once

#include <glad/gl.h>

#include <utility>

namespace aq::gl {

template <void (*Delete)(GLuint)>
class Handle {
 public:
  Handle() = default;
  explicit Handle(GLuint id) : id_(id) {}
  Handle(const Handle&) = delete;
  Handle& operator=(const Handle&) = delete;
  Handle(Handle&& other) noexcept : id_(std::exchange(other.id_, 0)) {}
  Handle& operator=(Handle&& other) noexcept {
    if (this != &other) {
      reset();
      id_ = std::exchange(other.id_, 0);
    }
    return *this;
  }
  ~Handle() { reset(); }

  GLuint get() const { return id_; }
  explicit operator bool() const { return id_ != 0; }
  GLuint release() { return std::exchange(id_, 0); }
  void reset(GLuint id = 0) {
    if (id_ != 0) Delete(id_);
    id_ = id;
  }

 private:
  GLuint id_ = 0;
};

inline void delete_texture(GLuint id) {
  glDeleteTextures(1, &id);
}
inline void delete_framebuffer(GLuint id) {
  glDeleteFramebuffers(1, &id);
}
inline void delete_buffer(GLuint id) {
  glDeleteBuffers(1, &id);
}
inline void delete_vertex_array(GLuint id) {
  glDeleteVertexArrays(1, &id);
}
inline void delete_program(GLuint id) {
  glDeleteProgram(id);
}
inline void delete_shader(GLuint id) {
  glDeleteShader(id);
}
inline void delete_query(GLuint id) {
  glDeleteQueries(1, &id);
}
inline void delete_renderbuffer(GLuint id) {
  glDeleteRenderbuffers(1, &id);
}
inline void delete_sampler(GLuint id) {
  glDeleteSamplers(1, &id);
}

using Texture = Handle<delete_texture>;
using Framebuffer = Handle<delete_framebuffer>;
using Buffer = Handle<delete_buffer>;
using VertexArray = Handle<delete_vertex_array>;
using Program = Handle<delete_program>;
using Shader = Handle<delete_shader>;
using Query = Handle<delete_query>;
using Renderbuffer = Handle<delete_renderbuffer>;
using Sampler = Handle<delete_sampler>;

inline Texture make_texture() {
  GLuint id = 0;
  glGenTextures(1, &id);
  return Texture(id);
}
inline Framebuffer make_framebuffer() {
  GLuint id = 0;
  glGenFramebuffers(1, &id);
  return Framebuffer(id);
}
inline Buffer make_buffer() {
  GLuint id = 0;
  glGenBuffers(1, &id);
  return Buffer(id);
}
inline VertexArray make_vertex_array() {
  GLuint id = 0;
  glGenVertexArrays(1, &id);
  return VertexArray(id);
}
inline Query make_query() {
  GLuint id = 0;
  glGenQueries(1, &id);
  return Query(id);
}

}  // namespace aq::gl
