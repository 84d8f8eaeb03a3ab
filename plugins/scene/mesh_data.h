// CPU meshes of the scene plugin and a builder that makes writing procedural shapes short.
// A MeshData is what one aq_mesh points into; the plugin keeps it alive between frames.
#pragma once

#include <glm/glm.hpp>

#include <cstdint>
#include <memory>
#include <vector>

namespace scene {

// Base colour pixels a mesh samples with its uvs: linear RGBA float, straight alpha, row 0 at
// v = 0 (aq_texture). Shared between the meshes (and frames) that use the same file.
struct Texture {
  std::vector<float> rgba;
  int width = 0;
  int height = 0;
  uint64_t revision = 0;  // unique per process; set when the pixels are made
};

struct MeshData {
  std::vector<float> positions;  // xyz per vertex, object space
  std::vector<float> normals;    // xyz per vertex
  std::vector<float> colors;     // rgb per vertex, linear albedo
  std::vector<uint32_t> indices;
  glm::mat4 model{1.0f};
  uint32_t object_id = 0;
  std::vector<float> uvs;                  // uv per vertex, or empty (untextured)
  std::shared_ptr<const Texture> texture;  // base colour, multiplies the vertex colours
  float alpha_cutoff = 0.0f;               // texture alpha below: a hole (cut-out cards)

  uint32_t vertex_count() const { return static_cast<uint32_t>(positions.size() / 3); }
  glm::vec3 position(uint32_t i) const {
    return {positions[3 * i], positions[3 * i + 1], positions[3 * i + 2]};
  }
};

// Appends vertices and triangles. `flat_triangle` gives each triangle its own three vertices
// and its face normal (the low-poly, colour-per-face look of the seed's models; smoothing
// later averages across the shared positions). `vertex` + `triangle` share vertices.
class MeshBuilder {
 public:
  explicit MeshBuilder(MeshData& mesh) : mesh_(mesh) {}

  uint32_t vertex(const glm::vec3& p, const glm::vec3& n, const glm::vec3& c) {
    mesh_.positions.insert(mesh_.positions.end(), {p.x, p.y, p.z});
    mesh_.normals.insert(mesh_.normals.end(), {n.x, n.y, n.z});
    mesh_.colors.insert(mesh_.colors.end(), {c.x, c.y, c.z});
    return mesh_.vertex_count() - 1;
  }
  void triangle(uint32_t a, uint32_t b, uint32_t c) {
    mesh_.indices.insert(mesh_.indices.end(), {a, b, c});
  }
  // Counter-clockwise seen from the side the normal points to. Degenerate triangles (zero
  // area, e.g. at the axis of a surface of revolution) are skipped.
  void flat_triangle(const glm::vec3& a, const glm::vec3& b, const glm::vec3& c,
                     const glm::vec3& color) {
    glm::vec3 n = glm::cross(b - a, c - a);
    float len = glm::length(n);
    if (!(len > 1e-12f)) return;
    n /= len;
    uint32_t i = vertex(a, n, color);
    vertex(b, n, color);
    vertex(c, n, color);
    triangle(i, i + 1, i + 2);
  }
  // a b c d counter-clockwise.
  void flat_quad(const glm::vec3& a, const glm::vec3& b, const glm::vec3& c, const glm::vec3& d,
                 const glm::vec3& color) {
    flat_triangle(a, b, c, color);
    flat_triangle(a, c, d, color);
  }

 private:
  MeshData& mesh_;
};

}  // namespace scene
