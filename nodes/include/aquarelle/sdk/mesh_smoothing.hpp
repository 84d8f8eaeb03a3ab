// Load-time normal smoothing for low-poly meshes (Paré-Vogt & Chaid §3.2): every vertex
// normal is averaged with its neighbours' normals, over the mesh's shared positions, a number
// of times (7 by default), so cel-shading bands follow the overall shape instead of the facets.
//
//   positions ──weld (tolerance, union-find)──► groups of coincident vertices
//   triangles ──────────────────────────────────► group adjacency (edges between groups)
//   n0(group) = normalised sum of its vertices' normals, each weighted by its corner angle
//   n_{k+1}(g) = normalise(n_k(g) + sum over adjacent groups h of w n_k(h))  (k < iterations)
//                with w = max(0, n_k(g) . n_k(h)): the other side of a thin wall is left out
//   vertex normal = n(group), tilted towards its own face normal where it (nearly) faces away,
//                   or the face normal itself where the group's normals cancelled
//
// Why welding by tolerance and not by hashing rounded coordinates: two copies of a corner that
// differ by 1e-7 can round into different cells and would stay unwelded (a visible seam).
// Here a vertex is compared against every vertex in the 27 surrounding cells of size
// `tolerance`, and welds are transitive (union-find). Copies of one exact position are welded
// to its first copy without that search (they have the same neighbours): a hostile file of
// 150,000 triangles on the same three corners made every vertex compare against all earlier
// ones (quadratic, over a minute; issue 40). Distinct vertices crowded into one cell are the
// same hang by another road, so a vertex compares against at most `kWeldScanLimit` vertices
// of a cell; a cell that holds more and that the vertex's tolerance sphere reaches (its box) is
// welded whole. The guarantee stays: vertices within `tolerance` always share a group; only
// inside such a crowd (more than 32 distinct vertices within one tolerance-sized cube, which
// no modelled mesh has) may vertices up to (1 + sqrt 3) x tolerance apart be welded too.
//
// Why the fallback: a double-sided part (two triangles with opposite windings on the same
// positions: a leaf, a fin, a plane seen from both sides) sums to a zero vector; normalising it
// gives NaN. Such groups are marked invalid and their vertices keep their own face normal.
//
// Positions are never moved, so the silhouette is exactly the input's. CPU only, header-only,
// no dependency beyond the standard library (the scene plugin and the tests both use it).
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <numeric>
#include <unordered_map>
#include <vector>

namespace aq::mesh {

struct SmoothingOptions {
  int iterations = 7;              // 0 leaves the normals untouched
  double weld_tolerance = 1e-5;    // relative to the mesh's bounding-box diagonal
  double cancel_threshold = 1e-3;  // |sum| / count below this: the normals cancelled
};

namespace detail {

using Vec3 = std::array<double, 3>;

inline Vec3 load(const std::vector<float>& v, size_t i) {
  return {v[3 * i], v[3 * i + 1], v[3 * i + 2]};
}
inline Vec3 add(const Vec3& a, const Vec3& b) {
  return {a[0] + b[0], a[1] + b[1], a[2] + b[2]};
}
inline Vec3 sub(const Vec3& a, const Vec3& b) {
  return {a[0] - b[0], a[1] - b[1], a[2] - b[2]};
}
inline Vec3 cross(const Vec3& a, const Vec3& b) {
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}
inline double dot(const Vec3& a, const Vec3& b) {
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}
inline double length(const Vec3& a) {
  return std::sqrt(dot(a, a));
}

struct UnionFind {
  std::vector<uint32_t> parent;
  explicit UnionFind(size_t n) : parent(n) { std::iota(parent.begin(), parent.end(), 0u); }
  uint32_t find(uint32_t x) {
    while (parent[x] != x) {
      parent[x] = parent[parent[x]];
      x = parent[x];
    }
    return x;
  }
  void unite(uint32_t a, uint32_t b) {
    a = find(a);
    b = find(b);
    if (a != b) parent[std::max(a, b)] = std::min(a, b);  // smallest index is the root
  }
};

struct CellKey {
  int64_t x, y, z;
  bool operator==(const CellKey&) const = default;
};
struct CellKeyHash {
  size_t operator()(const CellKey& k) const {
    uint64_t h = static_cast<uint64_t>(k.x) * 0x9E3779B97F4A7C15ull;
    h ^= static_cast<uint64_t>(k.y) * 0xC2B2AE3D27D4EB4Full + (h << 6) + (h >> 2);
    h ^= static_cast<uint64_t>(k.z) * 0x165667B19E3779F9ull + (h << 6) + (h >> 2);
    return static_cast<size_t>(h);
  }
};

// The vertices of one weld cell and their bounding box. `welded_whole`: the cell held more
// vertices than one search scans, so all of them are one group.
struct WeldCell {
  std::vector<uint32_t> vertices;
  Vec3 lo{1e300, 1e300, 1e300}, hi{-1e300, -1e300, -1e300};
  bool welded_whole = false;

  void add(uint32_t index, const Vec3& p) {
    vertices.push_back(index);
    for (int k = 0; k < 3; ++k) {
      lo[k] = std::min(lo[k], p[k]);
      hi[k] = std::max(hi[k], p[k]);
    }
  }
  double distance_to_box(const Vec3& p) const {
    Vec3 outside{};
    for (int k = 0; k < 3; ++k) outside[k] = std::max({lo[k] - p[k], 0.0, p[k] - hi[k]});
    return length(outside);
  }
};

inline constexpr size_t kWeldScanLimit = 32;

// Unites vertex `i` at `p` with the vertices of `cell` within `tol`, scanning at most
// kWeldScanLimit of them; past that the whole cell becomes one group with `i` (see the top).
inline void weld_against_cell(uint32_t i, const Vec3& p, WeldCell& cell,
                              const std::vector<float>& positions, double tol, UnionFind& sets) {
  if (!(cell.distance_to_box(p) <= tol)) return;
  if (cell.welded_whole) {
    sets.unite(i, cell.vertices.front());
    return;
  }
  if (cell.vertices.size() <= kWeldScanLimit) {
    for (uint32_t j : cell.vertices)
      if (length(sub(p, load(positions, j))) <= tol) sets.unite(i, j);
    return;
  }
  for (uint32_t j : cell.vertices) sets.unite(i, j);
  cell.welded_whole = true;
}

// A finite position's exact float bits.
struct ExactKey {
  uint32_t x, y, z;
  bool operator==(const ExactKey&) const = default;
};
struct ExactKeyHash {
  size_t operator()(const ExactKey& k) const {
    uint64_t h = (static_cast<uint64_t>(k.x) << 32 | k.y) * 0x9E3779B97F4A7C15ull;
    h ^= static_cast<uint64_t>(k.z) * 0xC2B2AE3D27D4EB4Full + (h >> 29);
    return static_cast<size_t>(h);
  }
};
inline ExactKey exact_key(const std::vector<float>& v, size_t i) {
  ExactKey key{};
  std::memcpy(&key.x, &v[3 * i], 4);
  std::memcpy(&key.y, &v[3 * i + 1], 4);
  std::memcpy(&key.z, &v[3 * i + 2], 4);
  return key;
}

}  // namespace detail

// Group index per vertex: vertices closer than `absolute_tolerance` (transitively) share one
// group. Group indices are dense, 0..group_count-1, in order of first appearance.
inline std::vector<uint32_t> weld_positions(const std::vector<float>& positions,
                                            double absolute_tolerance, uint32_t* group_count) {
  using namespace detail;
  const size_t n = positions.size() / 3;
  const double tol = std::max(absolute_tolerance, 1e-30);
  UnionFind sets(n);
  std::unordered_map<CellKey, WeldCell, CellKeyHash> cells;
  cells.reserve(n);
  std::unordered_map<ExactKey, uint32_t, ExactKeyHash> first_copy;
  first_copy.reserve(n);
  auto cell_of = [&](const Vec3& p) {
    return CellKey{static_cast<int64_t>(std::floor(p[0] / tol)),
                   static_cast<int64_t>(std::floor(p[1] / tol)),
                   static_cast<int64_t>(std::floor(p[2] / tol))};
  };
  for (uint32_t i = 0; i < n; ++i) {
    Vec3 p = load(positions, i);
    if (std::isfinite(p[0]) && std::isfinite(p[1]) && std::isfinite(p[2])) {
      auto [copy, first] = first_copy.try_emplace(exact_key(positions, i), i);
      if (!first) {
        sets.unite(i, copy->second);
        continue;
      }
    }
    CellKey c = cell_of(p);
    for (int64_t dx = -1; dx <= 1; ++dx)
      for (int64_t dy = -1; dy <= 1; ++dy)
        for (int64_t dz = -1; dz <= 1; ++dz) {
          auto it = cells.find(CellKey{c.x + dx, c.y + dy, c.z + dz});
          if (it != cells.end()) weld_against_cell(i, p, it->second, positions, tol, sets);
        }
    WeldCell& own = cells[c];
    if (own.welded_whole) sets.unite(i, own.vertices.front());
    own.add(i, p);
  }
  std::vector<uint32_t> group(n);
  std::vector<uint32_t> dense(n, UINT32_MAX);
  uint32_t next = 0;
  for (uint32_t i = 0; i < n; ++i) {
    uint32_t root = sets.find(i);
    if (dense[root] == UINT32_MAX) dense[root] = next++;
    group[i] = dense[root];
  }
  if (group_count != nullptr) *group_count = next;
  return group;
}

// Per-vertex normal from the faces that use the vertex (area weighted), or from the input
// normal when the faces cancel, or +y as the last resort. Always unit length and finite.
inline std::vector<float> vertex_face_normals(const std::vector<float>& positions,
                                              const std::vector<uint32_t>& indices,
                                              const std::vector<float>& input_normals) {
  using namespace detail;
  const size_t n = positions.size() / 3;
  std::vector<Vec3> sum(n, Vec3{0, 0, 0});
  for (size_t t = 0; t + 2 < indices.size(); t += 3) {
    uint32_t a = indices[t], b = indices[t + 1], c = indices[t + 2];
    if (a >= n || b >= n || c >= n) continue;
    Vec3 area2 = cross(sub(load(positions, b), load(positions, a)),
                       sub(load(positions, c), load(positions, a)));
    for (uint32_t v : {a, b, c}) sum[v] = add(sum[v], area2);
  }
  std::vector<float> out(3 * n);
  for (size_t i = 0; i < n; ++i) {
    Vec3 s = sum[i];
    double len = length(s);
    if (!(len > 1e-30) && input_normals.size() == positions.size()) {
      s = load(input_normals, i);
      len = length(s);
    }
    if (!(len > 1e-30) || !std::isfinite(len)) {
      s = {0, 1, 0};
      len = 1;
    }
    for (int k = 0; k < 3; ++k) out[3 * i + k] = static_cast<float>(s[k] / len);
  }
  return out;
}

namespace detail {

// The length of the bounding box's diagonal of the first n positions.
inline double bounding_diagonal(const std::vector<float>& positions, size_t n) {
  Vec3 lo{1e300, 1e300, 1e300}, hi{-1e300, -1e300, -1e300};
  for (size_t i = 0; i < n; ++i) {
    for (int k = 0; k < 3; ++k) {
      lo[k] = std::min(lo[k], static_cast<double>(positions[3 * i + k]));
      hi[k] = std::max(hi[k], static_cast<double>(positions[3 * i + k]));
    }
  }
  return length(sub(hi, lo));
}

// Adjacency between welded groups, as sorted unique neighbour lists.
inline std::vector<std::vector<uint32_t>> group_neighbours(const std::vector<uint32_t>& indices,
                                                           const std::vector<uint32_t>& group,
                                                           size_t n, uint32_t groups) {
  std::vector<std::vector<uint32_t>> neighbours(groups);
  for (size_t t = 0; t + 2 < indices.size(); t += 3) {
    uint32_t a = indices[t], b = indices[t + 1], c = indices[t + 2];
    if (a >= n || b >= n || c >= n) continue;
    uint32_t g[3] = {group[a], group[b], group[c]};
    for (int e = 0; e < 3; ++e) {
      uint32_t u = g[e], v = g[(e + 1) % 3];
      if (u == v) continue;
      neighbours[u].push_back(v);
      neighbours[v].push_back(u);
    }
  }
  for (auto& list : neighbours) {
    std::sort(list.begin(), list.end());
    list.erase(std::unique(list.begin(), list.end()), list.end());
  }
  return neighbours;
}

// Each vertex's normal counts with the angle of its corner in its triangle(s), so the
// starting normal of a position does not depend on how its faces were triangulated (a cube
// face split into two triangles counts 90 degrees at each corner, like a single quad would).
inline std::vector<double> corner_angles(const std::vector<float>& positions,
                                         const std::vector<uint32_t>& indices, size_t n) {
  std::vector<double> corner_angle(n, 0.0);
  for (size_t t = 0; t + 2 < indices.size(); t += 3) {
    uint32_t v[3] = {indices[t], indices[t + 1], indices[t + 2]};
    if (v[0] >= n || v[1] >= n || v[2] >= n) continue;
    for (int c = 0; c < 3; ++c) {
      Vec3 e1 = sub(load(positions, v[(c + 1) % 3]), load(positions, v[c]));
      Vec3 e2 = sub(load(positions, v[(c + 2) % 3]), load(positions, v[c]));
      double l1 = length(e1), l2 = length(e2);
      if (l1 > 0 && l2 > 0) {
        corner_angle[v[c]] += std::acos(std::clamp(dot(e1, e2) / (l1 * l2), -1.0, 1.0));
      }
    }
  }
  return corner_angle;
}

// One normal per welded group; a group normal is valid only when the unit normals summed into
// it did not cancel (their sum is longer than cancel_threshold times their total weight).
struct GroupNormals {
  std::vector<Vec3> normal;
  std::vector<char> valid;
  double cancel_threshold = 0;

  void normalise(uint32_t g, double total_weight) {
    Vec3& v = normal[g];
    double len = length(v);
    valid[g] = (len > cancel_threshold * total_weight && std::isfinite(len)) ? 1 : 0;
    v = valid[g] ? Vec3{v[0] / len, v[1] / len, v[2] / len} : Vec3{0, 0, 0};
  }
};

// The vertices' normals (`face` where one is zero or not finite) summed per group, each
// weighted by its corner angle.
inline GroupNormals initial_group_normals(const std::vector<float>& normals,
                                          const std::vector<float>& face,
                                          const std::vector<double>& corner_angle,
                                          const std::vector<uint32_t>& group, uint32_t groups,
                                          double cancel_threshold) {
  GroupNormals out{std::vector<Vec3>(groups, Vec3{0, 0, 0}), std::vector<char>(groups, 0),
                   cancel_threshold};
  std::vector<double> weight(groups, 0.0);
  for (size_t i = 0; i < corner_angle.size(); ++i) {
    Vec3 v = load(normals, i);
    double len = length(v);
    if (!(len > 1e-30) || !std::isfinite(len)) {
      v = load(face, i);
      len = 1.0;
    }
    double w = corner_angle[i] > 0 ? corner_angle[i] : 1e-6;
    out.normal[group[i]] =
        add(out.normal[group[i]], {w * v[0] / len, w * v[1] / len, w * v[2] / len});
    weight[group[i]] += w;
  }
  for (uint32_t g = 0; g < groups; ++g) out.normalise(g, weight[g]);
  return out;
}

// One smoothing iteration: each group's normal becomes the normalised sum of its own and its
// neighbours'. Neighbours count with max(0, cos(angle between normals)): across a thin wall (a
// pot's rim, a fin) the other side's normals face away and are left out instead of dragging the
// normals through the wall.
inline void smooth_step(GroupNormals& current, GroupNormals& next,
                        const std::vector<std::vector<uint32_t>>& neighbours) {
  const auto groups = static_cast<uint32_t>(neighbours.size());
  std::vector<double> next_weight(groups);
  for (uint32_t g = 0; g < groups; ++g) {
    Vec3 s = current.normal[g];
    double total = current.valid[g] ? 1.0 : 0.0;
    for (uint32_t h : neighbours[g]) {
      if (!current.valid[h]) continue;
      double w = current.valid[g] ? std::max(0.0, dot(current.normal[g], current.normal[h])) : 1.0;
      s = add(s, {w * current.normal[h][0], w * current.normal[h][1], w * current.normal[h][2]});
      total += w;
    }
    next.normal[g] = s;
    next_weight[g] = total;
  }
  for (uint32_t g = 0; g < groups; ++g) {
    next.valid[g] = current.valid[g];
    if (next_weight[g] > 0.0) {
      next.normalise(g, next_weight[g]);
    } else {
      next.valid[g] = 0;
    }
  }
  std::swap(current, next);
}

// A smoothed normal that (nearly) faces away from the vertex's own face would light it from
// behind: it is tilted just enough towards the face normal (dot = kMinFacing), which is
// continuous in the smoothed normal, so no hard seam appears where the rule starts to apply.
inline Vec3 facing_normal(const Vec3& smoothed, const Vec3& own) {
  constexpr double kMinFacing = 0.1;
  const double facing = dot(smoothed, own);
  if (facing >= kMinFacing) return smoothed;
  const double k = kMinFacing - facing;
  Vec3 tilted{smoothed[0] + k * own[0], smoothed[1] + k * own[1], smoothed[2] + k * own[2]};
  double len = length(tilted);
  return len > 1e-12 ? Vec3{tilted[0] / len, tilted[1] / len, tilted[2] / len} : own;
}

}  // namespace detail

// Smooths `normals` (xyz per vertex; computed from the faces when empty or the wrong size) in
// place. `positions` and `indices` are not modified.
inline void smooth_normals(const std::vector<float>& positions,
                           const std::vector<uint32_t>& indices, std::vector<float>& normals,
                           const SmoothingOptions& options = {}) {
  using namespace detail;
  const size_t n = positions.size() / 3;
  std::vector<float> face = vertex_face_normals(positions, indices, normals);
  if (normals.size() != positions.size()) normals = face;
  if (options.iterations <= 0 || n == 0) return;

  const double diagonal = bounding_diagonal(positions, n);
  uint32_t groups = 0;
  std::vector<uint32_t> group =
      weld_positions(positions, options.weld_tolerance * std::max(diagonal, 1e-30), &groups);
  const auto neighbours = group_neighbours(indices, group, n, groups);
  GroupNormals current = initial_group_normals(normals, face, corner_angles(positions, indices, n),
                                               group, groups, options.cancel_threshold);
  GroupNormals next = current;
  for (int iteration = 0; iteration < options.iterations; ++iteration)
    smooth_step(current, next, neighbours);

  for (size_t i = 0; i < n; ++i) {
    const Vec3 own = load(face, i);
    const Vec3 out = current.valid[group[i]] ? facing_normal(current.normal[group[i]], own) : own;
    for (int k = 0; k < 3; ++k) normals[3 * i + k] = static_cast<float>(out[k]);
  }
}

}  // namespace aq::mesh
