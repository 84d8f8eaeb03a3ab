// The head-on / moving split and the subdivision of hand_tremor (trembling_mesh.h).
#include "trembling_mesh.h"

#include <aquarelle/sdk/static_layer.hpp>
#include <glm/gtc/type_ptr.hpp>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstring>

namespace aq::tremor {
namespace {

constexpr double kTwoPi = 6.283185307179586;
// At most this many triangles in one moving part: n is lowered to stay under it.
constexpr double kMaxMovingTriangles = 262144.0;
constexpr int kMaxSubdivisions = 64;

glm::vec3 read3(const float* data, uint32_t v) {
  return glm::vec3(data[3 * v], data[3 * v + 1], data[3 * v + 2]);
}

// (a·i + b·j) + c·k over n, in this order whatever the triangle: the vertices on an edge two
// triangles share come out bit for bit the same from either (the third term is +0 there).
glm::vec3 blend(const glm::vec3& a, const glm::vec3& b, const glm::vec3& c, int i, int j, int k,
                int n) {
  return ((a * static_cast<float>(i) + b * static_cast<float>(j)) + c * static_cast<float>(k)) /
         static_cast<float>(n);
}

// Grazing at or below head_on: 0; from 2·head_on on, the grazing itself (the push as without
// head_on, so silhouettes wave as much as before); a ramp between (g itself for head_on 0).
double ramp(double grazing, double head_on) {
  if (!(head_on > 0.0) || grazing >= 2.0 * head_on) return grazing;
  return grazing * std::clamp((grazing - head_on) / head_on, 0.0, 1.0);
}

double grazing_of(const glm::vec3& p, const glm::vec3& n, const glm::mat4& model,
                  const glm::mat3& normal_matrix, const glm::vec3& eye) {
  const glm::vec3 world = glm::vec3(model * glm::vec4(p, 1.0f));
  const glm::vec3 world_normal = normal_matrix * n;
  const glm::vec3 to_eye = eye - world;
  const float ln = glm::length(world_normal), le = glm::length(to_eye);
  if (!(ln > 1e-12f) || !(le > 1e-12f)) return std::nan("");
  return 1.0 - std::abs(glm::dot(world_normal / ln, to_eye / le));
}

// The renderers bound what a moving mesh may cover by the boxes of its runs of
// DrawnOverLayer::kChunk triangles: a run across the end of a row would span the whole
// triangle (or two faces), so each row is closed with degenerate triangles (zero area: nothing
// drawn) on a vertex of its last one.
void pad_to_chunk(std::vector<uint32_t>& indices) {
  constexpr size_t kChunk = aq::DrawnOverLayer::kChunk;
  const uint32_t last = indices.back();
  while ((indices.size() / 3) % kChunk != 0) indices.insert(indices.end(), {last, last, last});
}

}  // namespace

uint64_t new_tremor_revision() {
  static std::atomic<uint64_t> next{uint64_t{1} << 62};
  return next.fetch_add(1);
}

double tremor_push(const glm::vec3& p, const glm::vec3& n, const glm::mat4& model,
                   const glm::mat3& normal_matrix, const TremblePlan& plan, double amount,
                   double phase) {
  const double grazing = grazing_of(p, n, model, normal_matrix, plan.eye);
  if (!std::isfinite(grazing)) return 0.0;
  const double f = plan.frequency;
  const double w = std::sin(kTwoPi * f * (p.x + 0.71 * p.y) + phase) *
                   std::cos(kTwoPi * f * (0.83 * p.z - 0.57 * p.y) + 1.3 * phase);
  const double push = amount * ramp(grazing, plan.head_on) * w;
  return std::isfinite(push) ? push : 0.0;
}

TremblingMesh::Key TremblingMesh::key_of(const aq_mesh& mesh, const float* uvs,
                                         const TremblePlan& plan) {
  Key key;
  key.revision = mesh.geometry_revision;
  key.positions = mesh.positions;
  key.vertex_count = mesh.vertex_count;
  key.index_count = mesh.index_count;
  std::copy(std::begin(mesh.model), std::end(mesh.model), key.model);
  key.uvs = uvs;
  key.frequency = plan.frequency;
  key.head_on = plan.head_on;
  key.segments = plan.segments;
  for (int k = 0; k < 3; ++k) key.eye[k] = plan.eye[k];
  return key;
}

void TremblingMesh::prepare(const aq_mesh& mesh, const float* uvs, const TremblePlan& plan) {
  const Key key = key_of(mesh, uvs, plan);
  if (prepared_ && key == key_) return;
  key_ = key;
  plan_ = plan;
  model_ = glm::make_mat4(mesh.model);
  normal_matrix_ = glm::transpose(glm::inverse(glm::mat3(model_)));
  split(mesh, uvs);
  head_on_revision_ = new_tremor_revision();
  prepared_ = true;
}

// A triangle moves when any of its vertices would (ramp > 0); the others are the head-on part.
void TremblingMesh::split(const aq_mesh& mesh, const float* uvs) {
  head_on_indices_.clear();
  std::vector<uint32_t> moving;
  std::vector<char> moves(mesh.vertex_count, 0);
  for (uint32_t v = 0; v < mesh.vertex_count; ++v) {
    const double g = grazing_of(read3(mesh.positions, v), read3(mesh.normals, v), model_,
                                normal_matrix_, plan_.eye);
    moves[v] = std::isfinite(g) && ramp(g, plan_.head_on) > 0.0 ? 1 : 0;
  }
  for (uint32_t t = 0; t + 2 < mesh.index_count && mesh.indices != nullptr; t += 3) {
    const uint32_t a = mesh.indices[t], b = mesh.indices[t + 1], c = mesh.indices[t + 2];
    if (a >= mesh.vertex_count || b >= mesh.vertex_count || c >= mesh.vertex_count) continue;
    auto& part = (moves[a] || moves[b] || moves[c]) ? moving : head_on_indices_;
    part.insert(part.end(), {a, b, c});
  }
  subdivide(mesh, uvs, moving);
}

void TremblingMesh::subdivide(const aq_mesh& mesh, const float* uvs,
                              const std::vector<uint32_t>& triangles) {
  rest_positions_.clear(), normals_.clear(), colors_.clear(), moving_uvs_.clear();
  moving_indices_.clear();
  const size_t count = triangles.size() / 3;
  if (count == 0) return;
  float longest = 0.0f;
  for (size_t i = 0; i < triangles.size(); i += 3) {
    for (int e = 0; e < 3; ++e) {
      const float l = glm::length(read3(mesh.positions, triangles[i + e]) -
                                  read3(mesh.positions, triangles[i + (e + 1) % 3]));
      if (std::isfinite(l)) longest = std::max(longest, l);
    }
  }
  double n = std::ceil(static_cast<double>(longest) * plan_.frequency * plan_.segments);
  n = std::min({n, std::floor(std::sqrt(kMaxMovingTriangles / static_cast<double>(count))),
                static_cast<double>(kMaxSubdivisions)});
  subdivisions_ = std::isfinite(n) ? std::max(1, static_cast<int>(n)) : 1;
  const int s = subdivisions_;
  auto index = [](int row, int j) { return static_cast<uint32_t>(row * (row + 1) / 2 + j); };
  for (size_t t = 0; t < triangles.size(); t += 3) {
    const uint32_t v[3] = {triangles[t], triangles[t + 1], triangles[t + 2]};
    const uint32_t base = static_cast<uint32_t>(rest_positions_.size() / 3);
    for (int row = 0; row <= s; ++row) {
      for (int j = 0; j <= row; ++j) {
        const int i = s - row, k = row - j;
        auto put = [&](const float* data, std::vector<float>& out) {
          const glm::vec3 p =
              blend(read3(data, v[0]), read3(data, v[1]), read3(data, v[2]), i, j, k, s);
          out.insert(out.end(), {p.x, p.y, p.z});
        };
        put(mesh.positions, rest_positions_);
        put(mesh.normals, normals_);
        if (mesh.colors != nullptr) put(mesh.colors, colors_);
        if (uvs != nullptr) {
          for (int c = 0; c < 2; ++c) {
            moving_uvs_.push_back(((uvs[2 * v[0] + c] * static_cast<float>(i) +
                                    uvs[2 * v[1] + c] * static_cast<float>(j)) +
                                   uvs[2 * v[2] + c] * static_cast<float>(k)) /
                                  static_cast<float>(s));
          }
        }
      }
    }
    for (int row = 0; row < s; ++row) {
      for (int j = 0; j <= row; ++j) {
        moving_indices_.insert(
            moving_indices_.end(),
            {base + index(row, j), base + index(row + 1, j + 1), base + index(row + 1, j)});
        if (j < row) {
          moving_indices_.insert(
              moving_indices_.end(),
              {base + index(row, j), base + index(row, j + 1), base + index(row + 1, j + 1)});
        }
      }
      if (s > 1) pad_to_chunk(moving_indices_);
    }
  }
  // Interpolated normals are shorter than unit inside a smooth mesh's triangle: unit again
  // (without subdivision the input's normals, as they are).
  for (size_t v = 0; s > 1 && v < normals_.size(); v += 3) {
    glm::vec3 n3(normals_[v], normals_[v + 1], normals_[v + 2]);
    const float l = glm::length(n3);
    if (l > 1e-12f && std::isfinite(l) && l != 1.0f) n3 /= l;
    normals_[v] = n3.x, normals_[v + 1] = n3.y, normals_[v + 2] = n3.z;
  }
}

void TremblingMesh::displace(double amount, double phase) {
  moved_positions_ = rest_positions_;
  for (size_t v = 0; v < rest_positions_.size(); v += 3) {
    const glm::vec3 p(rest_positions_[v], rest_positions_[v + 1], rest_positions_[v + 2]);
    const glm::vec3 n(normals_[v], normals_[v + 1], normals_[v + 2]);
    const double push = tremor_push(p, n, model_, normal_matrix_, plan_, amount, phase);
    if (push == 0.0) continue;
    for (int k = 0; k < 3; ++k) moved_positions_[v + k] = static_cast<float>(p[k] + n[k] * push);
  }
  moving_revision_ = new_tremor_revision();
}

aq_mesh TremblingMesh::head_on_part(const aq_mesh& in) const {
  aq_mesh part = in;
  part.indices = head_on_indices_.data();
  part.index_count = static_cast<uint32_t>(head_on_indices_.size());
  part.geometry_revision = head_on_revision_;
  return part;
}

aq_mesh TremblingMesh::moving_part(const aq_mesh& in) const {
  aq_mesh part = in;
  part.positions = moved_positions_.data();
  part.normals = normals_.data();
  part.colors = colors_.empty() ? nullptr : colors_.data();
  part.indices = moving_indices_.data();
  part.vertex_count = static_cast<uint32_t>(moved_positions_.size() / 3);
  part.index_count = static_cast<uint32_t>(moving_indices_.size());
  part.geometry_revision = moving_revision_;
  return part;
}

}  // namespace aq::tremor
