// The part of a rasterised scene that did not move, kept between frames (gbuffer, shadowmap).
// In an animation most meshes keep their vertex data and placement (the flagship: everything
// but the fish and the swaying seaweed); a node draws those once into cached targets and each
// frame copies them (glCopyImageSubData: a memory copy on llvmpipe, no shading) and draws only
// what moved over them. The depth test keeps the nearest surface whatever the order, so the
// targets are the same as drawing everything.
//
//   const auto& unchanged = unchanged_.update(scene);         // once per process() call
//   aq::Fnv1a key; unchanged_.mix_into(key); key.mix(view); ...
//   if (unchanged_.any()) {
//     layer_.ensure(generation, targets, n, &depth);
//     if (layer_.key != key.value && layer_.bind()) { draw the background and the unchanged
//       meshes; layer_.key = key.value; }
//     drawn_.restore(layer_, targets, n, &depth, outputs_kept);  // all, or where moved ones were
//   }
//   bind the targets, draw the meshes that moved; drawn_.record(layer_, boxes, unchanged, ...);
//
// Header-only; uses plugin.h(pp), glad, glm, gl_raii.hpp and view_bounds.hpp.
#pragma once

#include <aquarelle/plugin.h>
#include <aquarelle/plugin.hpp>
#include <aquarelle/sdk/gl_raii.hpp>
#include <aquarelle/sdk/region.hpp>
#include <aquarelle/sdk/view_bounds.hpp>

#include <glad/gl.h>
#include <glm/glm.hpp>

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

// The pixels a mesh whose world box is `box` (view_bounds::MeshBoxes) can cover when drawn with
// `view_projection` into a width x height target: the box's corners projected, one pixel wider
// on every side, clamped to the target; nothing for an empty box or one wholly outside the view.
// A box reaching behind the camera (the sand under it) is first clipped to the view frustum,
// whose every point projects (its projection is not bounded by the corners').
inline PixelRect covered_pixels(const view_bounds::Box& box, const glm::dmat4& view_projection,
                                int width, int height) {
  const PixelRect all{0, 0, width, height};
  if (box.empty()) return PixelRect{};
  std::vector<glm::dvec3> points;
  for (int corner = 0; corner < 8; ++corner) points.push_back(box.corner(corner));
  for (const glm::dvec3& p : points) {
    if (!((view_projection * glm::dvec4(p, 1.0)).w > 1e-9)) {
      const auto frustum = view_bounds::frustum_planes(view_projection);
      points = view_bounds::clip_box(box, frustum);
      if (points.empty()) return PixelRect{};
      break;
    }
  }
  double x0 = 1e300, y0 = 1e300, x1 = -1e300, y1 = -1e300;
  for (const glm::dvec3& p : points) {
    const glm::dvec4 clip = view_projection * glm::dvec4(p, 1.0);
    if (!(clip.w > 1e-9)) return all;
    const double x = (clip.x / clip.w * 0.5 + 0.5) * width;
    const double y = (clip.y / clip.w * 0.5 + 0.5) * height;
    if (!std::isfinite(x) || !std::isfinite(y)) return all;
    x0 = std::min(x0, x);
    x1 = std::max(x1, x);
    y0 = std::min(y0, y);
    y1 = std::max(y1, y);
  }
  auto clamp_to = [](double v, int size) {
    return static_cast<int>(std::clamp(v, 0.0, static_cast<double>(size)));
  };
  PixelRect rect{clamp_to(std::floor(x0) - 1.0, width), clamp_to(std::floor(y0) - 1.0, height),
                 clamp_to(std::ceil(x1) + 1.0, width), clamp_to(std::ceil(y1) + 1.0, height)};
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

  // Everything the unchanged meshes look like (as update() saw them), for the key of a layer
  // drawn from them.
  void mix_into(Fnv1a& key) const {
    for (uint32_t i = 0; i < unchanged_.size(); ++i) {
      if (!unchanged_[i]) continue;
      const State& state = previous_[i];
      key.mix(i);
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

// Textures shaped like a node's targets (each target's size and GL format) and, if it has one,
// its depth buffer, with a framebuffer over them, owned by the node between frames.
class CachedTargets {
 public:
  static constexpr uint32_t kMaxTargets = 8;

  // (Re)creates the textures when the context, a size or a format changed. Returns true when
  // it did, so whatever they held is gone (key is reset to 0).
  bool ensure(uint32_t gl_generation, const aq_image* targets, uint32_t count,
              const aq_image* depth) {
    Shape shape;
    shape.count = std::min(count, kMaxTargets);
    for (uint32_t i = 0; i < shape.count; ++i) shape.targets[i] = describe(targets[i]);
    if (depth != nullptr) shape.depth = describe(*depth);
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
    if (depth != nullptr) {
      glTextureStorage2D(depth_.create(), 1, shape.depth.internal_format, shape.depth.width,
                         shape.depth.height);
      glNamedFramebufferTexture(framebuffer, GL_DEPTH_ATTACHMENT, depth_.get(), 0);
    } else {
      depth_.reset();
    }
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
  void copy_to(const aq_image* targets, uint32_t count, const aq_image* depth) const {
    copy_rect_to(targets, count, depth, PixelRect{0, 0, targets[0].width, targets[0].height});
  }
  // The same for the pixels of `rect` only (targets and depth buffer of one size); a target of
  // texture 0 (an output nobody reads) is skipped.
  void copy_rect_to(const aq_image* targets, uint32_t count, const aq_image* depth,
                    const PixelRect& rect) const {
    const int w = rect.x1 - rect.x0, h = rect.y1 - rect.y0;
    if (w <= 0 || h <= 0) return;
    for (uint32_t i = 0; i < std::min(count, shape_.count); ++i) {
      if (targets[i].texture == 0) continue;
      glCopyImageSubData(colour_[i].get(), GL_TEXTURE_2D, 0, rect.x0, rect.y0, 0,
                         targets[i].texture, GL_TEXTURE_2D, 0, rect.x0, rect.y0, 0, w, h, 1);
    }
    if (depth != nullptr && depth_) {
      glCopyImageSubData(depth_.get(), GL_TEXTURE_2D, 0, rect.x0, rect.y0, 0, depth->texture,
                         GL_TEXTURE_2D, 0, rect.x0, rect.y0, 0, w, h, 1);
    }
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
    const GLuint name = texture_.get(gl_generation, width, height, GL_DEPTH_COMPONENT32F, kept);
    return aq_image{name, width, height, AQ_FORMAT_DEPTH32F};
  }

 private:
  gl::KeptTexture texture_;
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
  // everywhere. Until record(), nothing is known about the outputs. Returns the pixels that may
  // now differ from what the outputs held (those rects, or everything): with what record() adds,
  // the outputs' damage (aq_host::set_output_damage).
  Region restore(const CachedTargets& layer, const aq_image* targets, uint32_t count,
                 const aq_image* depth, bool outputs_kept) {
    Region changed;
    if (outputs_kept && valid_ && layer_key_ == layer.key &&
        layer_textures_ == layer.textures_made()) {
      // The copies cover more than covered_ (merged rects), but outside covered_ the targets
      // already hold the layer: only covered_ can change.
      for (const PixelRect& rect : moving_) layer.copy_rect_to(targets, count, depth, rect);
      changed = covered_;
    } else {
      layer.copy_to(targets, count, depth);
      changed = Region::everything();
    }
    valid_ = false;
    return changed;
  }

  // The pixels record() found the moving meshes may cover: their pieces' boxes, up to
  // Region::kMaxRects rects (the damage to declare; the copies use a merged superset).
  const Region& moving() const { return covered_; }

  // Triangles per box: two segments of a seaweed blade, a quarter ring of the fish's body. A
  // producer of moving meshes (hand_tremor) orders its triangles so each run of kChunk lies
  // close together: the boxes, and so the redrawn pixels, stay small.
  static constexpr uint32_t kChunk = 4;

  // After the moving meshes (those not `unchanged`) of `scene` were drawn with
  // `view_projection`; `world_boxes` are the scene's meshes' (view_bounds::MeshBoxes). What a
  // moving mesh may cover is the union of its triangle chunks' projected boxes (a swaying
  // blade's, not its cluster's), at most Region::kMaxDrawRects rects in all: each is a copy
  // per target at the next restore().
  void record(const CachedTargets& layer, const aq_scene& scene,
              const std::vector<view_bounds::Box>& world_boxes, const std::vector<bool>& unchanged,
              const glm::dmat4& view_projection, int width, int height) {
    std::vector<PixelRect> covered;
    for (size_t i = 0; i < world_boxes.size() && i < unchanged.size(); ++i) {
      if (unchanged[i]) continue;
      std::vector<view_bounds::Box> chunks =
          i < scene.mesh_count ? view_bounds::triangle_chunk_boxes(scene.meshes[i], kChunk)
                               : std::vector<view_bounds::Box>{};
      if (chunks.empty()) chunks.push_back(world_boxes[i]);
      for (const view_bounds::Box& box : chunks)
        covered.push_back(covered_pixels(box, view_projection, width, height));
    }
    Region region;
    region.add(covered);
    moving_ = region.for_drawing().rects();
    covered_ = region;
    layer_key_ = layer.key;
    layer_textures_ = layer.textures_made();
    valid_ = true;
  }

 private:
  bool valid_ = false;
  uint64_t layer_key_ = 0;
  uint64_t layer_textures_ = 0;
  std::vector<PixelRect> moving_;
  Region covered_;
};

}  // namespace aq
