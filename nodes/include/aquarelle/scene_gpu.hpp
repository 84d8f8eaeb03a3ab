// GPU copies of an aq_scene's meshes for nodes that rasterise a scene (gbuffer, shadowmap).
// A mesh is uploaded when its geometry_revision is new and freed when no mesh of the scene
// carries that revision any more, so static meshes are uploaded once and animated ones once
// per frame. Vertex layout: location 0 position, 1 normal, 2 colour (vec3 each, interleaved).
//
//   cache.update(scene, ctx.raw()->gl_generation);   // uploads what is new
//   for (i...) cache.draw(scene.meshes[i]);           // binds the VAO and draws
//
// Header-only; uses only plugin.h, glad and gl_raii.hpp.
#pragma once

#include <aquarelle/plugin.h>
#include <aquarelle/gl_raii.hpp>

#include <glad/gl.h>

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
      generation_ = gl_generation;
    }
    std::unordered_map<uint64_t, GpuMesh> kept;
    for (uint32_t i = 0; i < scene.mesh_count; ++i) {
      const aq_mesh& mesh = scene.meshes[i];
      auto it = meshes_.find(mesh.geometry_revision);
      if (it != meshes_.end()) {
        kept.emplace(it->first, std::move(it->second));
        meshes_.erase(it);
      } else if (kept.find(mesh.geometry_revision) == kept.end()) {
        kept.emplace(mesh.geometry_revision, upload(mesh));
      }
    }
    meshes_ = std::move(kept);  // what was not kept is deleted here
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

  static GpuMesh upload(const aq_mesh& mesh) {
    GpuMesh gpu;
    const uint32_t n = mesh.vertex_count;
    std::vector<float> interleaved(static_cast<size_t>(n) * 9);
    for (uint32_t v = 0; v < n; ++v) {
      float* out = &interleaved[static_cast<size_t>(v) * 9];
      for (int k = 0; k < 3; ++k) {
        out[k] = mesh.positions != nullptr ? mesh.positions[3 * v + k] : 0.0f;
        out[3 + k] = mesh.normals != nullptr ? mesh.normals[3 * v + k] : (k == 1 ? 1.0f : 0.0f);
        out[6 + k] = mesh.colors != nullptr ? mesh.colors[3 * v + k] : 0.8f;
      }
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
    glVertexArrayVertexBuffer(vao, 0, vbo, 0, 9 * sizeof(float));
    for (GLuint attribute = 0; attribute < 3; ++attribute) {
      glEnableVertexArrayAttrib(vao, attribute);
      glVertexArrayAttribFormat(vao, attribute, 3, GL_FLOAT, GL_FALSE,
                                attribute * 3 * sizeof(float));
      glVertexArrayAttribBinding(vao, attribute, 0);
    }
    glVertexArrayElementBuffer(vao, ibo);
    return gpu;
  }

  uint32_t generation_ = 0;
  std::unordered_map<uint64_t, GpuMesh> meshes_;
};

}  // namespace aq
