// The part of a rasterised scene that did not move, kept between frames (gbuffer, shadowmap).
// In an animation most meshes keep their vertex data and placement (the flagship: everything
// but the fish and the swaying seaweed); a node draws those once into cached targets and each
// frame copies them (glCopyImageSubData: a memory copy on llvmpipe, no shading) and draws only
// what moved over them. The depth test keeps the nearest surface whatever the order, so the
// targets are the same as drawing everything.
//
//   const auto& unchanged = static_meshes_.update(scene);     // once per process() call
//   aq::Fnv1a key; static_meshes_.mix_into(key, scene); key.mix(view); ...
//   if (static_meshes_.any()) {
//     if (layer_.ensure(generation, targets, n, depth) || layer_.key != key.value) {
//       layer_.bind(); draw the background and the unchanged meshes; layer_.key = key.value;
//     }
//     layer_.copy_to(targets, n, depth);   // then bind the targets and draw the rest
//   }
//
// Header-only; uses only plugin.h(pp), glad and gl_raii.hpp.
#pragma once

#include <aquarelle/plugin.h>
#include <aquarelle/plugin.hpp>
#include <aquarelle/sdk/gl_raii.hpp>

#include <glad/gl.h>

#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace aq {

// FNV-1a over raw bytes: the key of what a cached layer was drawn from.
struct Fnv1a {
  uint64_t value = 1469598103934665603ull;
  void mix(const void* data, size_t bytes) {
    const auto* p = static_cast<const unsigned char*>(data);
    for (size_t i = 0; i < bytes; ++i) value = (value ^ p[i]) * 1099511628211ull;
  }
  template <typename T>
  void mix(const T& v) {
    mix(&v, sizeof(T));
  }
};

// Which meshes have the vertex data, placement, id and surface they had on the previous call.
class UnchangedMeshes {
 public:
  const std::vector<bool>& update(const aq_scene& scene) {
    std::vector<State> now(scene.mesh_count);
    unchanged_.assign(scene.mesh_count, false);
    for (uint32_t i = 0; i < scene.mesh_count; ++i) {
      now[i] = state_of(scene, i);
      unchanged_[i] = i < previous_.size() && previous_[i] == now[i];
    }
    previous_ = std::move(now);
    return unchanged_;
  }
  bool any() const {
    return std::find(unchanged_.begin(), unchanged_.end(), true) != unchanged_.end();
  }
  const std::vector<bool>& flags() const { return unchanged_; }

  // Everything the unchanged meshes look like, for the key of a layer drawn from them.
  void mix_into(Fnv1a& key, const aq_scene& scene) const {
    for (uint32_t i = 0; i < scene.mesh_count && i < unchanged_.size(); ++i) {
      if (!unchanged_[i]) continue;
      key.mix(i);
      const State state = state_of(scene, i);
      key.mix(state.revision);
      key.mix(state.model);
      key.mix(state.object_id);
      key.mix(state.texture_revision);
      key.mix(state.alpha_cutoff);
    }
  }

 private:
  struct State {
    uint64_t revision = 0;
    std::array<float, 16> model{};
    uint32_t object_id = 0;
    uint64_t texture_revision = 0;  // 0 and null pixels: no texture
    const float* texture_pixels = nullptr;
    float alpha_cutoff = 0.0f;
    bool operator==(const State&) const = default;
  };

  static State state_of(const aq_scene& scene, uint32_t i) {
    State state;
    const aq_mesh& mesh = scene.meshes[i];
    state.revision = mesh.geometry_revision;
    std::copy(std::begin(mesh.model), std::end(mesh.model), state.model.begin());
    state.object_id = mesh.object_id;
    if (const aq_mesh_surface* surface = scene_surface(scene, i); surface != nullptr) {
      state.texture_revision = surface->base_color.revision;
      state.texture_pixels = surface->base_color.rgba;
      state.alpha_cutoff = surface->alpha_cutoff;
    }
    return state;
  }

  std::vector<State> previous_;
  std::vector<bool> unchanged_;
};

// Textures shaped like a node's targets (each target's size and GL format) and its depth
// buffer, with a framebuffer over them, owned by the node between frames.
class CachedTargets {
 public:
  static constexpr uint32_t kMaxTargets = 8;

  // (Re)creates the textures when the context, a size or a format changed. Returns true when
  // it did, so whatever they held is gone (key is reset to 0).
  bool ensure(uint32_t gl_generation, const aq_image* targets, uint32_t count,
              const aq_image& depth) {
    Shape shape;
    shape.count = std::min(count, kMaxTargets);
    for (uint32_t i = 0; i < shape.count; ++i) shape.targets[i] = describe(targets[i]);
    shape.depth = describe(depth);
    if (gl_generation == generation_ && shape == shape_) return false;
    if (gl_generation != generation_) {
      for (auto& texture : colour_) texture.forget();  // names of an old context mean nothing
      depth_.forget();
      framebuffer_.forget();
    }
    const GLuint framebuffer = framebuffer_.create();
    GLenum buffers[kMaxTargets];
    for (uint32_t i = 0; i < shape.count; ++i) {
      const Texel& t = shape.targets[i];
      glTextureStorage2D(colour_[i].create(), 1, t.internal_format, t.width, t.height);
      glNamedFramebufferTexture(framebuffer, GL_COLOR_ATTACHMENT0 + i, colour_[i].get(), 0);
      buffers[i] = GL_COLOR_ATTACHMENT0 + i;
    }
    for (uint32_t i = shape.count; i < kMaxTargets; ++i) colour_[i].reset();
    glNamedFramebufferDrawBuffers(framebuffer, static_cast<GLsizei>(shape.count), buffers);
    glTextureStorage2D(depth_.create(), 1, shape.depth.internal_format, shape.depth.width,
                       shape.depth.height);
    glNamedFramebufferTexture(framebuffer, GL_DEPTH_ATTACHMENT, depth_.get(), 0);
    generation_ = gl_generation;
    shape_ = shape;
    key = 0;
    return true;
  }

  // Binds the framebuffer and a viewport of the first target's size; false when the driver
  // calls it incomplete (the caller then draws everything into its targets instead).
  bool bind() const {
    glBindFramebuffer(GL_FRAMEBUFFER, framebuffer_.get());
    if (glCheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE) {
      glBindFramebuffer(GL_FRAMEBUFFER, 0);
      return false;
    }
    glViewport(0, 0, shape_.targets[0].width, shape_.targets[0].height);
    return true;
  }

  // Copies the cached content into the targets and depth buffer ensure() was shaped after.
  void copy_to(const aq_image* targets, uint32_t count, const aq_image& depth) const {
    for (uint32_t i = 0; i < std::min(count, shape_.count); ++i) {
      glCopyImageSubData(colour_[i].get(), GL_TEXTURE_2D, 0, 0, 0, 0, targets[i].texture,
                         GL_TEXTURE_2D, 0, 0, 0, 0, targets[i].width, targets[i].height, 1);
    }
    glCopyImageSubData(depth_.get(), GL_TEXTURE_2D, 0, 0, 0, 0, depth.texture, GL_TEXTURE_2D, 0, 0,
                       0, 0, depth.width, depth.height, 1);
  }

  uint64_t key = 0;  // what the cached content was drawn from; 0: nothing yet

 private:
  struct Texel {
    GLint internal_format = 0;
    int32_t width = 0, height = 0;
    bool operator==(const Texel&) const = default;
  };
  struct Shape {
    uint32_t count = 0;
    std::array<Texel, kMaxTargets> targets{};
    Texel depth;
    bool operator==(const Shape&) const = default;
  };

  // The GL format is read off the texture: the host may store an output narrower than the
  // format the node asked for (formats by need), and the copy needs the same format.
  static Texel describe(const aq_image& image) {
    Texel texel;
    glGetTextureLevelParameteriv(image.texture, 0, GL_TEXTURE_INTERNAL_FORMAT,
                                 &texel.internal_format);
    texel.width = image.width;
    texel.height = image.height;
    return texel;
  }

  uint32_t generation_ = 0;
  Shape shape_;
  std::array<gl::Texture, kMaxTargets> colour_;
  gl::Texture depth_;
  gl::Framebuffer framebuffer_;
};

}  // namespace aq
