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
#include <cmath>
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

// Pixels [x0, x1) x [y0, y1) of a target.
struct PixelRect {
  int x0 = 0, y0 = 0, x1 = 0, y1 = 0;
};

// The pixels mesh `mesh` can cover when drawn with `view_projection` into a width x height
// target: the projected box of its vertices (object space, placed by its model matrix), one
// pixel wider on every side, clamped to the target; the whole target when the box reaches
// behind the camera (its projection is then not bounded by the corners').
inline PixelRect covered_pixels(const aq_mesh& mesh, const float* view_projection, int width,
                                int height) {
  const PixelRect all{0, 0, width, height};
  if (mesh.vertex_count == 0 || mesh.positions == nullptr) return PixelRect{};
  float lo[3] = {mesh.positions[0], mesh.positions[1], mesh.positions[2]};
  float hi[3] = {lo[0], lo[1], lo[2]};
  for (uint32_t v = 1; v < mesh.vertex_count; ++v) {
    for (int k = 0; k < 3; ++k) {
      lo[k] = std::min(lo[k], mesh.positions[3 * v + k]);
      hi[k] = std::max(hi[k], mesh.positions[3 * v + k]);
    }
  }
  // clip = view_projection · model · corner (column-major 4x4 matrices).
  float m[16];
  for (int c = 0; c < 4; ++c) {
    for (int r = 0; r < 4; ++r) {
      float sum = 0.0f;
      for (int k = 0; k < 4; ++k) sum += view_projection[k * 4 + r] * mesh.model[c * 4 + k];
      m[c * 4 + r] = sum;
    }
  }
  float x0 = 1e30f, y0 = 1e30f, x1 = -1e30f, y1 = -1e30f;
  for (int corner = 0; corner < 8; ++corner) {
    const float p[3] = {(corner & 1) != 0 ? hi[0] : lo[0], (corner & 2) != 0 ? hi[1] : lo[1],
                        (corner & 4) != 0 ? hi[2] : lo[2]};
    float clip[4];
    for (int r = 0; r < 4; ++r)
      clip[r] = m[r] * p[0] + m[4 + r] * p[1] + m[8 + r] * p[2] + m[12 + r];
    if (!(clip[3] > 1e-6f)) return all;
    const float x = (clip[0] / clip[3] * 0.5f + 0.5f) * static_cast<float>(width);
    const float y = (clip[1] / clip[3] * 0.5f + 0.5f) * static_cast<float>(height);
    if (!std::isfinite(x) || !std::isfinite(y)) return all;
    x0 = std::min(x0, x);
    x1 = std::max(x1, x);
    y0 = std::min(y0, y);
    y1 = std::max(y1, y);
  }
  auto clamp_to = [](float v, int size) {
    return static_cast<int>(std::clamp(v, 0.0f, static_cast<float>(size)));
  };
  PixelRect rect{clamp_to(std::floor(x0) - 1.0f, width), clamp_to(std::floor(y0) - 1.0f, height),
                 clamp_to(std::ceil(x1) + 1.0f, width), clamp_to(std::ceil(y1) + 1.0f, height)};
  if (rect.x1 <= rect.x0 || rect.y1 <= rect.y0) return PixelRect{};
  return rect;
}

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
    ++textures_made_;
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
    copy_rect_to(targets, count, depth, PixelRect{0, 0, depth.width, depth.height});
  }
  // The same for the pixels of `rect` only (targets and depth buffer of one size).
  void copy_rect_to(const aq_image* targets, uint32_t count, const aq_image& depth,
                    const PixelRect& rect) const {
    const int w = rect.x1 - rect.x0, h = rect.y1 - rect.y0;
    if (w <= 0 || h <= 0) return;
    for (uint32_t i = 0; i < std::min(count, shape_.count); ++i) {
      glCopyImageSubData(colour_[i].get(), GL_TEXTURE_2D, 0, rect.x0, rect.y0, 0,
                         targets[i].texture, GL_TEXTURE_2D, 0, rect.x0, rect.y0, 0, w, h, 1);
    }
    glCopyImageSubData(depth_.get(), GL_TEXTURE_2D, 0, rect.x0, rect.y0, 0, depth.texture,
                       GL_TEXTURE_2D, 0, rect.x0, rect.y0, 0, w, h, 1);
  }

  uint64_t key = 0;  // what the cached content was drawn from; 0: nothing yet
  // Changes whenever ensure() made new textures (whatever key they are then drawn with).
  uint64_t textures_made() const { return textures_made_; }

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
  uint64_t textures_made_ = 0;
  Shape shape_;
  std::array<gl::Texture, kMaxTargets> colour_;
  gl::Texture depth_;
  gl::Framebuffer framebuffer_;
};

// A node's own depth buffer, kept between calls: with outputs the host kept (output_kept), the
// next call redraws only what moved and needs this call's depths around it.
class KeptDepth {
 public:
  // The depth buffer for a width x height target; `kept` false when it was (re)created.
  aq_image get(uint32_t gl_generation, int width, int height, bool* kept) {
    *kept = texture_ && generation_ == gl_generation && width_ == width && height_ == height;
    if (!*kept) {
      if (generation_ != gl_generation) texture_.forget();  // the old context's name
      glTextureStorage2D(texture_.create(), 1, GL_DEPTH_COMPONENT32F, width, height);
      generation_ = gl_generation;
      width_ = width;
      height_ = height;
    }
    return aq_image{texture_.get(), width, height, AQ_FORMAT_DEPTH32F};
  }

 private:
  gl::Texture texture_;
  uint32_t generation_ = 0;
  int width_ = 0, height_ = 0;
};

// What a node's last call left in its outputs over the cached layer: which layer, and the
// pixels its moving meshes may cover. With every output kept by the host and the same layer,
// restoring the layer there is enough; otherwise the whole layer is copied.
class DrawnOverLayer {
 public:
  // When a call draws its outputs without the layer: nothing is known about them then.
  void invalidate() { valid_ = false; }

  // Puts the layer into the targets: only where the last call's moving meshes were when the
  // outputs are as it left them (`outputs_kept`, the host's word) over the same layer, else
  // everywhere. Until record(), nothing is known about the outputs.
  void restore(const CachedTargets& layer, const aq_image* targets, uint32_t count,
               const aq_image& depth, bool outputs_kept) {
    if (outputs_kept && valid_ && layer_key_ == layer.key &&
        layer_textures_ == layer.textures_made()) {
      for (const PixelRect& rect : moving_) layer.copy_rect_to(targets, count, depth, rect);
    } else {
      layer.copy_to(targets, count, depth);
    }
    valid_ = false;
  }

  // After the moving meshes (those not `unchanged`) were drawn with `view_projection`.
  void record(const CachedTargets& layer, const aq_scene& scene, const std::vector<bool>& unchanged,
              const float* view_projection, int width, int height) {
    moving_.clear();
    for (uint32_t i = 0; i < scene.mesh_count && i < unchanged.size(); ++i) {
      if (!unchanged[i])
        moving_.push_back(covered_pixels(scene.meshes[i], view_projection, width, height));
    }
    layer_key_ = layer.key;
    layer_textures_ = layer.textures_made();
    valid_ = true;
  }

 private:
  bool valid_ = false;
  uint64_t layer_key_ = 0;
  uint64_t layer_textures_ = 0;
  std::vector<PixelRect> moving_;
};

}  // namespace aq
