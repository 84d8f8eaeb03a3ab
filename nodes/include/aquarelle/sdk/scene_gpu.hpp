// GPU copies of an aq_scene's meshes for nodes that rasterise a scene (gbuffer, shadowmap).
// A mesh is uploaded when its geometry_revision is new and freed when no mesh of the scene
// carries that revision any more, so static meshes are uploaded once and animated ones once
// per frame. Vertex layout: location 0 position, 1 normal, 2 colour (vec3 each, interleaved).
//
//   cache.update(scene, ctx.raw()->gl_generation);   // uploads what is new
//   for (i...) cache.draw(scene.meshes[i]);           // binds the VAO and draws
//
// Header-only; uses only plugin.h(pp), glad and gl_raii.hpp.
#pragma once

#include <aquarelle/plugin.h>
#include <aquarelle/plugin.hpp>
#include <aquarelle/sdk/gl_raii.hpp>

#include <glad/gl.h>

#include <algorithm>
#include <cstdint>
#include <unordered_map>
#include <vector>

namespace aq {

class SceneMeshCache {
 public:
  void update(const aq_scene& scene, uint32_t gl_generation) {
    if (gl_generation != generation_) {
      // The old context's names mean nothing in the new one: drop them without GL calls.
      for (auto& [revision, mesh] : meshes_) mesh.forget();
      meshes_.clear();
      for (auto& [revision, texture] : textures_) texture.forget();
      textures_.clear();
      white_.forget();
      generation_ = gl_generation;
    }
    std::unordered_map<uint64_t, GpuMesh> kept;
    std::unordered_map<uint64_t, gl::Texture> kept_textures;
    for (uint32_t i = 0; i < scene.mesh_count; ++i) {
      const aq_mesh& mesh = scene.meshes[i];
      const aq_mesh_surface* surface = scene_surface(scene, i);
      auto it = meshes_.find(mesh.geometry_revision);
      if (it != meshes_.end()) {
        kept.emplace(it->first, std::move(it->second));
        meshes_.erase(it);
      } else if (kept.find(mesh.geometry_revision) == kept.end()) {
        kept.emplace(mesh.geometry_revision,
                     upload(mesh, surface != nullptr ? surface->uvs : nullptr));
      }
      if (surface == nullptr || !usable(surface->base_color)) continue;
      const uint64_t revision = surface->base_color.revision;
      if (auto texture = textures_.find(revision); texture != textures_.end()) {
        kept_textures.emplace(revision, std::move(texture->second));
        textures_.erase(texture);
      } else if (kept_textures.find(revision) == kept_textures.end()) {
        kept_textures.emplace(revision, upload_texture(surface->base_color));
      }
    }
    meshes_ = std::move(kept);  // what was not kept is deleted here
    textures_ = std::move(kept_textures);
  }

  // Binds mesh i's base colour texture on texture unit `unit` (a white texel when it has
  // none) and returns its alpha cut-off (0: opaque). Call after update().
  float bind_surface(const aq_scene& scene, uint32_t i, GLuint unit) const {
    const aq_mesh_surface* surface = scene_surface(scene, i);
    GLuint texture = surface_texture(scene, i);
    if (texture == 0) {
      if (white_.get() == 0) {
        const aq_texture white_texel{kWhite, 1, 1, 0};
        white_ = upload_texture(white_texel);
      }
      texture = white_.get();
    }
    glBindTextureUnit(unit, texture);
    return texture != white_.get() && surface != nullptr ? surface->alpha_cutoff : 0.0f;
  }

  // Mesh i's uploaded base colour texture, 0 when it has none (bind_surface binds white then):
  // a shader variant without the texture read and the cut-out's discard serves those meshes.
  GLuint surface_texture(const aq_scene& scene, uint32_t i) const {
    const aq_mesh_surface* surface = scene_surface(scene, i);
    if (surface == nullptr || surface->uvs == nullptr || !usable(surface->base_color)) return 0;
    auto it = textures_.find(surface->base_color.revision);
    return it != textures_.end() ? it->second.get() : 0;
  }

  // Binds the mesh's vertex array and draws its triangles; the caller sets the uniforms.
  void draw(const aq_mesh& mesh) const {
    auto it = meshes_.find(mesh.geometry_revision);
    if (it == meshes_.end() || it->second.index_count == 0) return;
    glBindVertexArray(it->second.vertex_array.get());
    glDrawElements(GL_TRIANGLES, it->second.index_count, GL_UNSIGNED_INT, nullptr);
    glBindVertexArray(0);
  }

  size_t uploaded_count() const { return meshes_.size(); }

 private:
  struct GpuMesh {
    gl::VertexArray vertex_array;
    gl::Buffer vertices;
    gl::Buffer indices;
    GLsizei index_count = 0;
    void forget() {
      vertex_array.forget();
      vertices.forget();
      indices.forget();
    }
  };

  static constexpr float kWhite[4] = {1.0f, 1.0f, 1.0f, 1.0f};
  static constexpr int kStride = 11;  // floats per vertex

  static bool usable(const aq_texture& texture) {
    return texture.rgba != nullptr && texture.width > 0 && texture.height > 0 &&
           texture.width <= 16384 && texture.height <= 16384;
  }

  static gl::Texture upload_texture(const aq_texture& pixels) {
    gl::Texture texture;
    GLuint name = texture.create();
    int levels = 1;
    for (int side = std::max(pixels.width, pixels.height); side > 1; side /= 2) ++levels;
    glTextureStorage2D(name, levels, GL_RGBA16F, pixels.width, pixels.height);
    glTextureSubImage2D(name, 0, 0, 0, pixels.width, pixels.height, GL_RGBA, GL_FLOAT, pixels.rgba);
    glTextureParameteri(name, GL_TEXTURE_MIN_FILTER, GL_LINEAR_MIPMAP_LINEAR);
    glTextureParameteri(name, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    glTextureParameteri(name, GL_TEXTURE_WRAP_S, GL_REPEAT);
    glTextureParameteri(name, GL_TEXTURE_WRAP_T, GL_REPEAT);
    glGenerateTextureMipmap(name);
    return texture;
  }

  static GpuMesh upload(const aq_mesh& mesh, const float* uvs) {
    GpuMesh gpu;
    const uint32_t n = mesh.vertex_count;
    std::vector<float> interleaved(static_cast<size_t>(n) * kStride);
    for (uint32_t v = 0; v < n; ++v) {
      float* out = &interleaved[static_cast<size_t>(v) * kStride];
      for (int k = 0; k < 3; ++k) {
        out[k] = mesh.positions != nullptr ? mesh.positions[3 * v + k] : 0.0f;
        out[3 + k] = mesh.normals != nullptr ? mesh.normals[3 * v + k] : (k == 1 ? 1.0f : 0.0f);
        out[6 + k] = mesh.colors != nullptr ? mesh.colors[3 * v + k] : 0.8f;
      }
      out[9] = uvs != nullptr ? uvs[2 * v] : 0.0f;
      out[10] = uvs != nullptr ? uvs[2 * v + 1] : 0.0f;
    }
    // Indices past the vertex count would read outside the buffer: drop those triangles.
    std::vector<uint32_t> indices;
    indices.reserve(mesh.index_count);
    for (uint32_t t = 0; t + 2 < mesh.index_count && mesh.indices != nullptr; t += 3) {
      if (mesh.indices[t] < n && mesh.indices[t + 1] < n && mesh.indices[t + 2] < n) {
        indices.insert(indices.end(), {mesh.indices[t], mesh.indices[t + 1], mesh.indices[t + 2]});
      }
    }
    gpu.index_count = static_cast<GLsizei>(indices.size());
    if (n == 0 || indices.empty()) return gpu;
    GLuint vbo = gpu.vertices.create();
    glNamedBufferStorage(vbo, static_cast<GLsizeiptr>(interleaved.size() * sizeof(float)),
                         interleaved.data(), 0);
    GLuint ibo = gpu.indices.create();
    glNamedBufferStorage(ibo, static_cast<GLsizeiptr>(indices.size() * sizeof(uint32_t)),
                         indices.data(), 0);
    GLuint vao = gpu.vertex_array.create();
    glVertexArrayVertexBuffer(vao, 0, vbo, 0, kStride * sizeof(float));
    for (GLuint attribute = 0; attribute < 4; ++attribute) {
      glEnableVertexArrayAttrib(vao, attribute);
      glVertexArrayAttribFormat(vao, attribute, attribute == 3 ? 2 : 3, GL_FLOAT, GL_FALSE,
                                attribute * 3 * sizeof(float));
      glVertexArrayAttribBinding(vao, attribute, 0);
    }
    glVertexArrayElementBuffer(vao, ibo);
    return gpu;
  }

  uint32_t generation_ = 0;
  std::unordered_map<uint64_t, GpuMesh> meshes_;
  std::unordered_map<uint64_t, gl::Texture> textures_;  // by aq_texture::revision
  mutable gl::Texture white_;                           // made on first use
};

}  // namespace aq
