// Procedural shapes of the scene plugin (see shapes.h). Everything is low-poly and flat-shaded
// on purpose: the seed's models have one colour per face, and load-time normal smoothing
// (mesh_smoothing.hpp) turns the facets into smooth cel bands afterwards.
#include "shapes.h"

#include <glm/gtc/matrix_transform.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <utility>

namespace scene {

namespace {

constexpr float kPi = 3.14159265358979f;

// A flat triangle wound so that its normal points along `outward` (a hint: centroid minus an
// inside point), which spares every generator from getting its winding right by hand.
void outward_triangle(MeshBuilder& builder, const glm::vec3& a, const glm::vec3& b,
                      const glm::vec3& c, const glm::vec3& outward, const glm::vec3& color) {
  if (glm::dot(glm::cross(b - a, c - a), outward) < 0.0f) {
    builder.flat_triangle(a, c, b, color);
  } else {
    builder.flat_triangle(a, b, c, color);
  }
}

// Two unit vectors perpendicular to `axis` and to each other.
std::pair<glm::vec3, glm::vec3> basis_around(const glm::vec3& axis) {
  glm::vec3 helper = std::abs(axis.y) < 0.9f ? glm::vec3(0, 1, 0) : glm::vec3(1, 0, 0);
  glm::vec3 u = glm::normalize(glm::cross(axis, helper));
  return {u, glm::cross(axis, u)};
}

glm::vec3 jitter(Random& random, const glm::vec3& color, float amount) {
  return glm::clamp(color * static_cast<float>(1.0 + random.range(-amount, amount)), 0.0f, 1.0f);
}

// Tapered tube from p0 (radius r0) to p1 (radius r1), `sides` facets, without caps.
void add_tube(MeshBuilder& builder, const glm::vec3& p0, const glm::vec3& p1, float r0, float r1,
              int sides, const glm::vec3& color) {
  glm::vec3 axis = glm::normalize(p1 - p0);
  auto [u, v] = basis_around(axis);
  for (int j = 0; j < sides; ++j) {
    float t0 = 2.0f * kPi * j / sides, t1 = 2.0f * kPi * (j + 1) / sides;
    glm::vec3 d0 = std::cos(t0) * u + std::sin(t0) * v;
    glm::vec3 d1 = std::cos(t1) * u + std::sin(t1) * v;
    glm::vec3 a = p0 + r0 * d0, b = p0 + r0 * d1, c = p1 + r1 * d1, d = p1 + r1 * d0;
    glm::vec3 outward = d0 + d1;
    outward_triangle(builder, a, b, c, outward, color);
    outward_triangle(builder, a, c, d, outward, color);
  }
}

void add_coral_branch(MeshBuilder& builder, Random& random, const glm::vec3& base,
                      const glm::vec3& direction, float length, float radius, int depth,
                      const glm::vec3& color) {
  glm::vec3 tip = base + direction * length;
  float tip_radius = radius * 0.72f;
  add_tube(builder, base, tip, radius, tip_radius, 5, color);
  if (depth == 0) {
    // Close the branch with a short cone so its end is not a hole.
    add_tube(builder, tip, tip + direction * tip_radius * 1.5f, tip_radius, 1e-4f, 5, color);
    return;
  }
  int children = random.integer(2, 3);
  auto [u, v] = basis_around(direction);
  double spin = random.range(0.0, 2.0 * kPi);
  for (int k = 0; k < children; ++k) {
    float around = static_cast<float>(spin + 2.0 * kPi * k / children);
    float tilt = static_cast<float>(random.range(0.35, 0.75));
    glm::vec3 side = std::cos(around) * u + std::sin(around) * v;
    glm::vec3 child = glm::normalize(std::cos(tilt) * direction + std::sin(tilt) * side);
    child = glm::normalize(child + glm::vec3(0, 0.35f, 0));  // corals grow towards the light
    add_coral_branch(builder, random, tip, child,
                     length * static_cast<float>(random.range(0.62, 0.8)), tip_radius, depth - 1,
                     color);
  }
}

}  // namespace

void bake_transform(MeshData& mesh, const glm::mat4& transform) {
  glm::mat3 normal_matrix = glm::transpose(glm::inverse(glm::mat3(transform)));
  for (uint32_t i = 0; i < mesh.vertex_count(); ++i) {
    glm::vec3 p = glm::vec3(transform * glm::vec4(mesh.position(i), 1.0f));
    glm::vec3 n(mesh.normals[3 * i], mesh.normals[3 * i + 1], mesh.normals[3 * i + 2]);
    n = normal_matrix * n;
    float len = glm::length(n);
    n = len > 0.0f ? n / len : glm::vec3(0, 1, 0);
    for (int k = 0; k < 3; ++k) {
      mesh.positions[3 * i + k] = p[k];
      mesh.normals[3 * i + k] = n[k];
    }
  }
}

void add_lathe(MeshData& mesh, const std::vector<glm::vec2>& profile, int segments,
               const glm::vec3& color) {
  MeshBuilder builder(mesh);
  auto at = [&](size_t i, int j) {
    float t = 2.0f * kPi * static_cast<float>(j % segments) / static_cast<float>(segments);
    return glm::vec3(profile[i].x * std::cos(t), profile[i].y, profile[i].x * std::sin(t));
  };
  for (size_t i = 0; i + 1 < profile.size(); ++i) {
    for (int j = 0; j < segments; ++j) {
      builder.flat_quad(at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j + 1), color);
    }
  }
}

void add_box(MeshData& mesh, const glm::vec3& lo, const glm::vec3& hi, const glm::vec3& color) {
  MeshBuilder builder(mesh);
  glm::vec3 centre = 0.5f * (lo + hi);
  auto corner = [&](int i) {
    return glm::vec3((i & 1) ? hi.x : lo.x, (i & 2) ? hi.y : lo.y, (i & 4) ? hi.z : lo.z);
  };
  constexpr std::array<std::array<int, 4>, 6> kFaces = {
      {{0, 1, 3, 2}, {4, 5, 7, 6}, {0, 1, 5, 4}, {2, 3, 7, 6}, {0, 2, 6, 4}, {1, 3, 7, 5}}};
  for (const auto& f : kFaces) {
    glm::vec3 a = corner(f[0]), b = corner(f[1]), c = corner(f[2]), d = corner(f[3]);
    glm::vec3 outward = 0.25f * (a + b + c + d) - centre;
    outward_triangle(builder, a, b, c, outward, color);
    outward_triangle(builder, a, c, d, outward, color);
  }
}

void add_plane(MeshData& mesh, float half_size, int cells, const glm::vec3& color,
               bool double_sided) {
  MeshBuilder builder(mesh);
  float step = 2.0f * half_size / static_cast<float>(cells);
  for (int side = 0; side < (double_sided ? 2 : 1); ++side) {
    for (int i = 0; i < cells; ++i) {
      for (int j = 0; j < cells; ++j) {
        float x0 = -half_size + i * step, x1 = x0 + step;
        float z0 = -half_size + j * step, z1 = z0 + step;
        glm::vec3 a(x0, 0, z0), b(x0, 0, z1), c(x1, 0, z1), d(x1, 0, z0);
        if (side == 0) {
          builder.flat_quad(a, b, c, d, color);  // faces +y
        } else {
          builder.flat_quad(a, d, c, b, color);  // the same positions, facing -y
        }
      }
    }
  }
}

void add_clay_pot(MeshData& mesh, int segments, const glm::vec3& color) {
  // (radius, height): up the outside, over the rim, down the inside to the inner floor.
  const std::vector<glm::vec2> profile = {
      {0.0f, 0.0f},   {0.30f, 0.0f},  {0.42f, 0.08f}, {0.54f, 0.34f}, {0.57f, 0.60f},
      {0.50f, 0.90f}, {0.34f, 1.10f}, {0.30f, 1.20f}, {0.37f, 1.30f}, {0.37f, 1.35f},
      {0.31f, 1.35f}, {0.25f, 1.21f}, {0.29f, 1.10f}, {0.45f, 0.90f}, {0.52f, 0.60f},
      {0.49f, 0.35f}, {0.36f, 0.14f}, {0.0f, 0.10f}};
  add_lathe(mesh, profile, segments, color);
}

void add_rock(MeshData& mesh, Random& random, const glm::vec3& color) {
  const float phi = 1.6180340f;
  std::vector<glm::vec3> v = {{-1, phi, 0}, {1, phi, 0}, {-1, -phi, 0}, {1, -phi, 0},
                              {0, -1, phi}, {0, 1, phi}, {0, -1, -phi}, {0, 1, -phi},
                              {phi, 0, -1}, {phi, 0, 1}, {-phi, 0, -1}, {-phi, 0, 1}};
  for (auto& p : v) p = glm::normalize(p);
  std::vector<std::array<uint32_t, 3>> faces = {
      {0, 11, 5},  {0, 5, 1},  {0, 1, 7},  {0, 7, 10}, {0, 10, 11}, {1, 5, 9}, {5, 11, 4},
      {11, 10, 2}, {10, 7, 6}, {7, 1, 8},  {3, 9, 4},  {3, 4, 2},   {3, 2, 6}, {3, 6, 8},
      {3, 8, 9},   {4, 9, 5},  {2, 4, 11}, {6, 2, 10}, {8, 6, 7},   {9, 8, 1}};
  // One subdivision: 80 faces, still clearly low-poly once pushed about.
  std::map<std::pair<uint32_t, uint32_t>, uint32_t> midpoints;
  auto midpoint = [&](uint32_t a, uint32_t b) {
    auto key = std::minmax(a, b);
    auto it = midpoints.find(key);
    if (it != midpoints.end()) return it->second;
    v.push_back(glm::normalize(v[a] + v[b]));
    uint32_t index = static_cast<uint32_t>(v.size() - 1);
    midpoints.emplace(key, index);
    return index;
  };
  std::vector<std::array<uint32_t, 3>> fine;
  for (const auto& f : faces) {
    uint32_t ab = midpoint(f[0], f[1]), bc = midpoint(f[1], f[2]), ca = midpoint(f[2], f[0]);
    fine.push_back({f[0], ab, ca});
    fine.push_back({f[1], bc, ab});
    fine.push_back({f[2], ca, bc});
    fine.push_back({ab, bc, ca});
  }
  for (auto& p : v) p *= static_cast<float>(random.range(0.8, 1.12));
  MeshBuilder builder(mesh);
  for (const auto& f : fine) {
    glm::vec3 a = v[f[0]], b = v[f[1]], c = v[f[2]];
    outward_triangle(builder, a, b, c, a + b + c, jitter(random, color, 0.06f));
  }
}

void add_coral(MeshData& mesh, Random& random, const glm::vec3& color) {
  MeshBuilder builder(mesh);
  int trunks = random.integer(1, 2);
  for (int t = 0; t < trunks; ++t) {
    glm::vec3 lean(static_cast<float>(random.range(-0.25, 0.25)), 1.0f,
                   static_cast<float>(random.range(-0.25, 0.25)));
    glm::vec3 base(static_cast<float>(random.range(-0.1, 0.1)), -0.05f,
                   static_cast<float>(random.range(-0.1, 0.1)));
    add_coral_branch(builder, random, base, glm::normalize(lean),
                     static_cast<float>(random.range(0.35, 0.5)), 0.09f, 3, color);
  }
}

void add_shell(MeshData& mesh, const glm::vec3& color) {
  MeshBuilder builder(mesh);
  const int ribs = 9, rings = 4, steps = 2 * ribs;
  const float spread = 2.4f;  // radians of the fan
  glm::vec3 light = glm::clamp(color * 1.08f, 0.0f, 1.0f);
  auto point = [&](int ring, int step) {
    float rf = static_cast<float>(ring) / rings;
    float angle = -0.5f * spread + spread * static_cast<float>(step) / steps;
    float rib = (step % 2 == 0) ? 0.05f * rf : 0.0f;  // ridges grow towards the rim
    float height = 0.26f * std::sin(kPi * rf) + rib;  // domed, down to the sand at hinge and rim
    return glm::vec3(rf * std::sin(angle), height, rf * std::cos(angle));
  };
  for (int ring = 0; ring < rings; ++ring) {
    for (int step = 0; step < steps; ++step) {
      glm::vec3 a = point(ring, step), b = point(ring + 1, step), c = point(ring + 1, step + 1),
                d = point(ring, step + 1);
      glm::vec3 face_color = (step % 2 == 0) ? color : light;
      outward_triangle(builder, a, b, c, glm::vec3(0, 1, 0), face_color);
      outward_triangle(builder, a, c, d, glm::vec3(0, 1, 0), face_color);
    }
  }
}

void add_starfish(MeshData& mesh, const glm::vec3& color) {
  MeshBuilder builder(mesh);
  const glm::vec3 centre(0, 0.16f, 0);
  glm::vec3 darker = color * 0.85f;
  for (int arm = 0; arm < 5; ++arm) {
    float a = 2.0f * kPi * arm / 5.0f;
    float a_prev = a - kPi / 5.0f, a_next = a + kPi / 5.0f;
    glm::vec3 tip(std::cos(a), 0.03f, std::sin(a));
    glm::vec3 ridge(0.5f * std::cos(a), 0.12f, 0.5f * std::sin(a));
    glm::vec3 valley_prev(0.36f * std::cos(a_prev), 0.05f, 0.36f * std::sin(a_prev));
    glm::vec3 valley_next(0.36f * std::cos(a_next), 0.05f, 0.36f * std::sin(a_next));
    const glm::vec3 up(0, 1, 0);
    outward_triangle(builder, centre, valley_prev, ridge, up, color);
    outward_triangle(builder, ridge, valley_prev, tip, up, darker);
    outward_triangle(builder, centre, ridge, valley_next, up, darker);
    outward_triangle(builder, ridge, tip, valley_next, up, color);
  }
}

void add_seaweed_blade(MeshData& mesh, const glm::vec3& root, float height, float width,
                       float facing, const glm::vec2& bend, float amplitude, float phase,
                       const glm::vec3& color) {
  MeshBuilder builder(mesh);
  const int segments = 8;
  glm::vec3 side(std::cos(facing), 0.0f, std::sin(facing));
  glm::vec3 bend3(bend.x, 0.0f, bend.y);
  auto centre = [&](float s) {
    float offset = amplitude * s * s * std::sin(phase - 1.5f * s);
    return root + glm::vec3(0, height * s, 0) + bend3 * offset;
  };
  auto half_width = [&](float s) { return 0.5f * width * (1.0f - 0.85f * s); };
  for (int i = 0; i < segments; ++i) {
    float s0 = static_cast<float>(i) / segments, s1 = static_cast<float>(i + 1) / segments;
    glm::vec3 c0 = centre(s0), c1 = centre(s1);
    glm::vec3 a = c0 - side * half_width(s0), b = c0 + side * half_width(s0);
    glm::vec3 c = c1 + side * half_width(s1), d = c1 - side * half_width(s1);
    glm::vec3 shade = color * (0.9f + 0.2f * s1);  // tips catch more light in the seed's renders
    builder.flat_quad(a, b, c, d, glm::clamp(shade, 0.0f, 1.0f));
  }
}

void add_fish(MeshData& mesh, double time, float wave_amplitude, const glm::vec3& body_color,
              const glm::vec3& fin_color) {
  MeshBuilder builder(mesh);
  // Travelling body wave, stronger towards the tail (x decreasing).
  const float k = 7.0f, omega = 8.0f;
  auto deform = [&](glm::vec3 p) {
    float w = std::clamp((0.5f - p.x) / 1.25f, 0.0f, 1.0f);
    p.z += wave_amplitude * w * w * std::sin(k * p.x - omega * static_cast<float>(time));
    return p;
  };
  // Body: elliptical sections along x, narrower in z (a fish is flat sideways).
  const std::vector<glm::vec2> profile = {{0.50f, 0.0f},   {0.42f, 0.09f},   {0.30f, 0.15f},
                                          {0.12f, 0.18f},  {-0.08f, 0.16f},  {-0.25f, 0.11f},
                                          {-0.38f, 0.06f}, {-0.47f, 0.035f}, {-0.49f, 0.0f}};
  const int sides = 8;
  glm::vec3 belly = glm::clamp(body_color * glm::vec3(1.0f, 1.25f, 2.2f), 0.0f, 1.0f);
  auto ring = [&](size_t i, int j) {
    float t = 2.0f * kPi * static_cast<float>(j % sides) / sides;
    return glm::vec3(profile[i].x, profile[i].y * std::cos(t), 0.55f * profile[i].y * std::sin(t));
  };
  for (size_t i = 0; i + 1 < profile.size(); ++i) {
    for (int j = 0; j < sides; ++j) {
      glm::vec3 a = ring(i, j), b = ring(i + 1, j), c = ring(i + 1, j + 1), d = ring(i, j + 1);
      glm::vec3 axis_point(0.5f * (a.x + c.x), 0, 0);
      glm::vec3 outward = 0.25f * (a + b + c + d) - axis_point;
      glm::vec3 color = (a.y + c.y < 0.0f) ? belly : body_color;
      outward_triangle(builder, deform(a), deform(b), deform(c), outward, color);
      outward_triangle(builder, deform(a), deform(c), deform(d), outward, color);
    }
  }
  // Forked tail fin and a dorsal fin: thin, single-sided (the gbuffer lights both sides).
  const glm::vec3 side(0, 0, 1);
  outward_triangle(builder, deform({-0.44f, 0.03f, 0}), deform({-0.76f, 0.25f, 0}),
                   deform({-0.64f, 0.0f, 0}), side, fin_color);
  outward_triangle(builder, deform({-0.44f, -0.03f, 0}), deform({-0.64f, 0.0f, 0}),
                   deform({-0.76f, -0.25f, 0}), side, fin_color);
  outward_triangle(builder, deform({0.12f, 0.17f, 0}), deform({-0.16f, 0.14f, 0}),
                   deform({-0.06f, 0.31f, 0}), side, fin_color);
  // Eyes: small dark triangles just outside the body on both sides.
  for (float s : {1.0f, -1.0f}) {
    glm::vec3 e(0.35f, 0.045f, s * 0.075f);
    outward_triangle(
        builder, deform(e + glm::vec3(0.03f, 0, 0)), deform(e + glm::vec3(-0.02f, 0.03f, 0)),
        deform(e + glm::vec3(-0.02f, -0.03f, 0)), glm::vec3(0, 0, s), glm::vec3(0.03f));
  }
}

}  // namespace scene
