// Tiny RAII owners for the GL objects a plugin keeps in its instance state between frames
// (vertex buffers, vertex arrays, samplers). Plugins may not use the core's gl_objects.h (they see
// only plugin.h and glad), so this header depends on nothing else.
//
// A GL name belongs to the context that created it. When the host switches contexts
// (ctx.gl_generation changes) the old names are meaningless in the new one: `forget()` drops
// them without calling glDelete*, and the plugin creates fresh ones.
#pragma once

#include <glad/gl.h>

#include <utility>

namespace aq::gl {

enum class Kind { kBuffer, kVertexArray, kTexture, kFramebuffer, kSampler };

template <Kind K>
class Object {
 public:
  Object() = default;
  ~Object() { reset(); }
  Object(const Object&) = delete;
  Object& operator=(const Object&) = delete;
  Object(Object&& other) noexcept : name_(std::exchange(other.name_, 0u)) {}
  Object& operator=(Object&& other) noexcept {
    if (this != &other) {
      reset();
      name_ = std::exchange(other.name_, 0u);
    }
    return *this;
  }

  // Creates the object (deleting the one held, if any) and returns its name.
  GLuint create() {
    reset();
    if constexpr (K == Kind::kBuffer) glCreateBuffers(1, &name_);
    if constexpr (K == Kind::kVertexArray) glCreateVertexArrays(1, &name_);
    if constexpr (K == Kind::kTexture) glCreateTextures(GL_TEXTURE_2D, 1, &name_);
    if constexpr (K == Kind::kFramebuffer) glCreateFramebuffers(1, &name_);
    if constexpr (K == Kind::kSampler) glCreateSamplers(1, &name_);
    return name_;
  }
  void reset() {
    if (name_ == 0) return;
    if constexpr (K == Kind::kBuffer) glDeleteBuffers(1, &name_);
    if constexpr (K == Kind::kVertexArray) glDeleteVertexArrays(1, &name_);
    if constexpr (K == Kind::kTexture) glDeleteTextures(1, &name_);
    if constexpr (K == Kind::kFramebuffer) glDeleteFramebuffers(1, &name_);
    if constexpr (K == Kind::kSampler) glDeleteSamplers(1, &name_);
    name_ = 0;
  }
  // The context that owned the name is gone: drop it without a GL call.
  void forget() { name_ = 0; }
  GLuint get() const { return name_; }
  explicit operator bool() const { return name_ != 0; }

 private:
  GLuint name_ = 0;
};

using Buffer = Object<Kind::kBuffer>;
using VertexArray = Object<Kind::kVertexArray>;
using Texture = Object<Kind::kTexture>;
using Framebuffer = Object<Kind::kFramebuffer>;
using Sampler = Object<Kind::kSampler>;

// A texture a node keeps between calls (a depth buffer, a scratch format the host's pool does
// not have), made again when the context, the size or the format changes.
class KeptTexture {
 public:
  // The texture for width x height in `internal_format`; `kept` false when it was (re)made, so
  // whatever it held is gone.
  GLuint get(uint32_t gl_generation, int width, int height, GLenum internal_format, bool* kept) {
    *kept = texture_ && generation_ == gl_generation && width_ == width && height_ == height &&
            format_ == internal_format;
    if (!*kept) {
      if (generation_ != gl_generation) texture_.forget();  // the old context's name
      glTextureStorage2D(texture_.create(), 1, internal_format, width, height);
      generation_ = gl_generation;
      width_ = width;
      height_ = height;
      format_ = internal_format;
    }
    return texture_.get();
  }

 private:
  Texture texture_;
  uint32_t generation_ = 0;
  int width_ = 0, height_ = 0;
  GLenum format_ = 0;
};

}  // namespace aq::gl
