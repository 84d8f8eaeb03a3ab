// One trembling mesh of `hand_tremor`, split in two so the renderers redraw only what moves:
//
//   head-on part  the triangles whose every vertex is seen within `head_on` of head-on (grazing
//                 g = 1 − |n̂·v̂| ≤ head_on): they do not move, so they are handed on with the
//                 input's vertex data and a revision that stays while the view and the mesh do
//                 (the gbuffer and control_map keep them in their cached layers)
//   moving part   the other triangles, each subdivided into n² (the same n for the whole mesh,
//                 so neighbours share their edge vertices: no cracks), n chosen so an edge is at
//                 most 1 / (segments · f) object units: a coarse mesh (a 12-triangle box) gets
//                 the vertices a wave of frequency f needs, and its silhouette waves instead of
//                 its faces tilting (seed 002's "things to improve": tremor needs dense meshes)
//
// Each moving vertex is pushed along its normal by amount · ramp(g) · w(p, t), with
// ramp(g) = g · clamp((g − head_on) / head_on, 0, 1) (= g when head_on is 0, and from
// 2·head_on on: silhouettes move as much as without it) and w the travelling wave of
// hand_tremor.cpp. The split and the subdivision are kept between frames; each frame
// only pushes the moving vertices again.
#pragma once

#include <aquarelle/plugin.h>

#include <glm/glm.hpp>

#include <cstdint>
#include <vector>

namespace aq::tremor {

struct TremblePlan {
  double frequency = 4.0;  // waves per object-space unit (the object's tremor_frequency)
  double head_on = 0.0;    // grazing at or below which nothing moves
  int segments = 0;        // vertices per wavelength along an edge; 0: the mesh's own only
  glm::vec3 eye{0.0f};     // camera position, world space
};

// The push of one vertex (object-space position p, normal n) of a mesh placed by `model`:
// amount · ramp(grazing) · wave, or 0 where it is not finite (a NaN normal stays put).
double tremor_push(const glm::vec3& p, const glm::vec3& n, const glm::mat4& model,
                   const glm::mat3& normal_matrix, const TremblePlan& plan, double amount,
                   double phase);

class TremblingMesh {
 public:
  // Splits `mesh` (with its surface's uvs, or null) again when it, its placement or the plan
  // changed since the last call; else keeps the split.
  void prepare(const aq_mesh& mesh, const float* uvs, const TremblePlan& plan);
  // Pushes the moving vertices for this frame (a new revision for the moving part).
  void displace(double amount, double phase);

  bool has_head_on() const { return !head_on_indices_.empty(); }
  bool has_moving() const { return !moving_indices_.empty(); }
  // The two parts as meshes (the input's placement, id and flags); the head-on part reads the
  // input's vertex arrays, which must outlive it (they are the input scene's).
  aq_mesh head_on_part(const aq_mesh& in) const;
  aq_mesh moving_part(const aq_mesh& in) const;
  const float* moving_uvs() const { return moving_uvs_.empty() ? nullptr : moving_uvs_.data(); }
  // Subdivisions per edge of the moving triangles (1: the mesh's own vertices).
  int subdivisions() const { return subdivisions_; }

 private:
  struct Key {
    uint64_t revision = 0;
    const float* positions = nullptr;
    uint32_t vertex_count = 0, index_count = 0;
    float model[16] = {};
    const float* uvs = nullptr;
    double frequency = 0.0, head_on = 0.0;
    int segments = 0;
    float eye[3] = {};
    bool operator==(const Key&) const = default;
  };
  static Key key_of(const aq_mesh& mesh, const float* uvs, const TremblePlan& plan);
  void split(const aq_mesh& mesh, const float* uvs);
  void subdivide(const aq_mesh& mesh, const float* uvs, const std::vector<uint32_t>& triangles);

  Key key_{};
  bool prepared_ = false;
  TremblePlan plan_;
  glm::mat4 model_{1.0f};
  glm::mat3 normal_matrix_{1.0f};
  uint64_t head_on_revision_ = 0;
  uint64_t moving_revision_ = 0;
  int subdivisions_ = 1;
  std::vector<uint32_t> head_on_indices_;
  // The moving part at rest (object space) and as pushed this frame.
  std::vector<float> rest_positions_, normals_, colors_, moving_uvs_, moved_positions_;
  std::vector<uint32_t> moving_indices_;
};

// A revision no other mesh of this process has (a range of its own, apart from the scene
// plugin's counter, which starts at 1).
uint64_t new_tremor_revision();

}  // namespace aq::tremor
