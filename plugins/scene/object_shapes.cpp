#include "object_shapes.h"

#include "random.h"
#include "shapes.h"

#include <cmath>
#include <string>

namespace scene {

namespace {

constexpr float kPi = 3.14159265358979f;

// A unit square in the y = 0 plane facing +y, uv (0,0) at (-0.5, 0, +0.5) and v growing
// towards -z (an image laid on the floor reads upright from a camera looking down -z).
void add_textured_plane(MeshData& mesh) {
  MeshBuilder builder(mesh);
  const glm::vec3 n(0, 1, 0), c(1.0f);
  const glm::vec2 corners[4] = {{-0.5f, 0.5f}, {0.5f, 0.5f}, {0.5f, -0.5f}, {-0.5f, -0.5f}};
  for (const glm::vec2& p : corners) {
    builder.vertex({p.x, 0.0f, p.y}, n, c);
    mesh.uvs.insert(mesh.uvs.end(), {p.x + 0.5f, 0.5f - p.y});
  }
  builder.triangle(0, 1, 2);
  builder.triangle(0, 2, 3);
}

// A cut-out card: a unit square standing in the z = 0 plane on y = 0, facing +z, uv (0,0) at
// its bottom-left. One-sided geometry; the g-buffer lights whichever side is seen.
void add_card(MeshData& mesh) {
  MeshBuilder builder(mesh);
  const glm::vec3 n(0, 0, 1), c(1.0f);
  const glm::vec2 corners[4] = {{-0.5f, 0.0f}, {0.5f, 0.0f}, {0.5f, 1.0f}, {-0.5f, 1.0f}};
  for (const glm::vec2& p : corners) {
    builder.vertex({p.x, p.y, 0.0f}, n, c);
    mesh.uvs.insert(mesh.uvs.end(), {p.x + 0.5f, p.y});
  }
  builder.triangle(0, 1, 2);
  builder.triangle(0, 2, 3);
}

std::vector<glm::vec2> sphere_profile(int rings) {
  std::vector<glm::vec2> profile;
  for (int i = 0; i <= rings; ++i) {
    const float a = -0.5f * kPi + kPi * static_cast<float>(i) / static_cast<float>(rings);
    profile.push_back({0.5f * std::cos(a), 0.5f * std::sin(a)});
  }
  return profile;
}

}  // namespace

void make_object_shape(std::string_view name, double time, uint64_t seed, MeshData& mesh) {
  const glm::vec3 white(1.0f);
  Random random(seed);
  if (name == "cube") {
    add_box(mesh, glm::vec3(-0.5f), glm::vec3(0.5f), white);
  } else if (name == "sphere") {
    add_lathe(mesh, sphere_profile(12), 24, white);
  } else if (name == "plane") {
    add_textured_plane(mesh);
  } else if (name == "card") {
    add_card(mesh);
  } else if (name == "pot") {
    add_clay_pot(mesh, 24, glm::vec3(0.72f, 0.38f, 0.22f));
  } else if (name == "rock") {
    add_rock(mesh, random, glm::vec3(0.45f, 0.42f, 0.4f));
  } else if (name == "coral") {
    add_coral(mesh, random, glm::vec3(0.9f, 0.35f, 0.45f));
  } else if (name == "shell") {
    add_shell(mesh, glm::vec3(0.95f, 0.85f, 0.75f));
  } else if (name == "starfish") {
    add_starfish(mesh, glm::vec3(0.98f, 0.5f, 0.18f));
  } else if (name == "fish") {
    add_fish(mesh, time, 0.07f, glm::vec3(1.0f, 0.62f, 0.12f), glm::vec3(0.95f, 0.32f, 0.12f));
  }
}

void box_project_uvs(MeshData& mesh) {
  const uint32_t n = mesh.vertex_count();
  if (n == 0) return;
  glm::vec3 lo(1e30f), hi(-1e30f);
  for (uint32_t v = 0; v < n; ++v) {
    lo = glm::min(lo, mesh.position(v));
    hi = glm::max(hi, mesh.position(v));
  }
  const glm::vec3 size = glm::max(hi - lo, glm::vec3(1e-6f));
  mesh.uvs.assign(static_cast<size_t>(n) * 2, 0.0f);
  for (uint32_t v = 0; v < n; ++v) {
    const glm::vec3 p = (mesh.position(v) - lo) / size;
    const glm::vec3 a =
        glm::abs(glm::vec3(mesh.normals[3 * v], mesh.normals[3 * v + 1], mesh.normals[3 * v + 2]));
    glm::vec2 uv = a.x >= a.y && a.x >= a.z ? glm::vec2(p.z, p.y)
                   : a.y >= a.z             ? glm::vec2(p.x, 1.0f - p.z)
                                            : glm::vec2(p.x, p.y);
    mesh.uvs[2 * v] = uv.x;
    mesh.uvs[2 * v + 1] = uv.y;
  }
}

}  // namespace scene
