// The "underwater" preset, composed like the seed's Figure 1 (Paré-Vogt & Chaid): a sand tray
// displaced by two octaves of Perlin noise as in seed 001 (a broad, slow octave plus a small,
// fast one) with a procedural sand colour, low-poly rocks, branching corals at the back,
// seaweed clusters, shells and starfish in front, two clay pots in the middle and a fish
// swimming a loop above them. Everything comes from `seed` through our own generator.
//
// Layout (world units ~ metres, y up, camera looking towards -z):
//
//        z = -6   corals, seaweed, rocks
//        z =  0   pots, rocks          fish loop at y ~ 2.4 around (0.6, -0.5)
//        z = +4   shells, starfish
#include "perlin.h"
#include "presets.h"
#include "shapes.h"

#include <glm/gtc/matrix_transform.hpp>

#include <algorithm>
#include <cmath>

namespace scene {

namespace {

constexpr float kTrayHalfSize = 8.0f;
constexpr int kTrayCells = 96;  // at detail 1 (a full-size render)

// Height of the sand and its colour at (x, z); objects are set on this surface.
class SandField {
 public:
  explicit SandField(uint64_t seed) : broad_(seed ^ 0x5A4Dull), fine_(seed ^ 0x5A4E5Aull) {}

  float height(float x, float z) const {
    double broad = 0.55 * broad_(x * 0.11, z * 0.11);            // seed 001's slow octave
    double fine = 0.12 * fine_(x * 0.5 + 31.7, z * 0.5 + 17.3);  // and its fast one
    double ripple = 0.015 * std::sin(6.0 * x + 2.0 * fine_(x * 0.2, z * 0.2));
    return static_cast<float>(broad + fine + ripple);
  }

  glm::vec3 color(float x, float z, float h) const {
    const glm::vec3 sand(0.78f, 0.68f, 0.50f);
    double mottle = 1.0 + 0.10 * fine_(x * 1.7 + 5.1, z * 1.7 - 2.3);
    double grain = 1.0 + 0.06 * broad_(x * 9.0, z * 9.0);
    double hollows = 0.9 + 0.1 * std::clamp((h + 0.5) / 1.0, 0.0, 1.0);
    return glm::clamp(sand * static_cast<float>(mottle * grain * hollows), 0.0f, 1.0f);
  }

 private:
  Perlin2 broad_, fine_;
};

MeshData make_sand(const SandField& sand, double detail) {
  MeshData mesh;
  MeshBuilder builder(mesh);
  // The tray is most of the triangles of the scene, and on llvmpipe every triangle costs setup
  // time in the g-buffer and again in the shadow map: a proxy render (detail < 1) shows each
  // cell on fewer pixels and gets fewer cells.
  const int n = std::max(16, static_cast<int>(std::lround(kTrayCells * detail)));
  for (int i = 0; i <= n; ++i) {
    for (int j = 0; j <= n; ++j) {
      float x = -kTrayHalfSize + 2.0f * kTrayHalfSize * i / n;
      float z = -kTrayHalfSize + 2.0f * kTrayHalfSize * j / n;
      float h = sand.height(x, z);
      builder.vertex({x, h, z}, {0, 1, 0}, sand.color(x, z, h));
    }
  }
  for (int i = 0; i < n; ++i) {
    for (int j = 0; j < n; ++j) {
      uint32_t a = i * (n + 1) + j, b = a + 1, c = a + (n + 1) + 1, d = a + (n + 1);
      builder.triangle(a, b, c);  // (x, z+1) then (x+1, z+1): faces +y
      builder.triangle(a, c, d);
    }
  }
  return mesh;
}

// Picks spots on the sand that keep a distance from everything already placed; gives up on a
// spot after a fixed number of tries so the result stays deterministic and bounded.
class Placer {
 public:
  bool place(Random& random, glm::vec2 x_range, glm::vec2 z_range, float radius, glm::vec2* out) {
    for (int attempt = 0; attempt < 40; ++attempt) {
      glm::vec2 p(static_cast<float>(random.range(x_range.x, x_range.y)),
                  static_cast<float>(random.range(z_range.x, z_range.y)));
      bool free = true;
      for (const auto& [q, r] : taken_) {
        if (glm::length(p - q) < radius + r) free = false;
      }
      if (free) {
        taken_.push_back({p, radius});
        *out = p;
        return true;
      }
    }
    return false;
  }
  void reserve(glm::vec2 p, float radius) { taken_.push_back({p, radius}); }

 private:
  std::vector<std::pair<glm::vec2, float>> taken_;
};

glm::mat4 placed(const SandField& sand, glm::vec2 at, float sink, float yaw, glm::vec3 scale,
                 float tilt = 0.0f) {
  glm::mat4 m = glm::translate(glm::mat4(1.0f), {at.x, sand.height(at.x, at.y) - sink, at.y});
  m = glm::rotate(m, yaw, glm::vec3(0, 1, 0));
  m = glm::rotate(m, tilt, glm::vec3(1, 0, 0));
  return glm::scale(m, scale);
}

struct Blade {
  glm::vec3 root;
  float height, width, facing, phase;
  glm::vec2 bend;
};

// What every placement step of the underwater preset works on: the preset being filled, the
// seed's generator (each kind forks its own stream), the sand, the placer that keeps objects
// apart, and the next object id.
struct Layout {
  Preset& preset;
  Random& random;
  const SandField& sand;
  Placer& placer;
  uint32_t next_id = 1;

  void add_static(MeshData mesh) {
    mesh.object_id = next_id++;
    preset.static_meshes.push_back(std::move(mesh));
  }
};

// Two clay pots in the middle, the second smaller and leaning.
void place_pots(Layout& layout) {
  const SandField& sand = layout.sand;
  const glm::vec3 terracotta(0.66f, 0.32f, 0.18f);
  Random r = layout.random.fork(1);
  glm::vec2 a(-1.6f + static_cast<float>(r.range(-0.3, 0.3)), 0.2f);
  glm::vec2 b(-0.3f + static_cast<float>(r.range(-0.3, 0.3)), 1.4f);
  layout.placer.reserve(a, 0.8f);
  layout.placer.reserve(b, 0.6f);
  MeshData pot_a, pot_b;
  add_clay_pot(pot_a, 14, terracotta);
  bake_transform(pot_a,
                 placed(sand, a, 0.05f, static_cast<float>(r.range(0, 6.28)), glm::vec3(1.15f)));
  layout.add_static(std::move(pot_a));
  add_clay_pot(pot_b, 14, terracotta * 0.92f);
  bake_transform(pot_b, placed(sand, b, 0.08f, static_cast<float>(r.range(0, 6.28)),
                               glm::vec3(0.75f), static_cast<float>(r.range(0.12, 0.3))));
  layout.add_static(std::move(pot_b));
}

void place_rocks(Layout& layout) {
  const SandField& sand = layout.sand;
  Random rocks = layout.random.fork(2);
  for (int i = 0; i < 7; ++i) {
    float size = static_cast<float>(rocks.range(0.35, 0.9));
    glm::vec2 at;
    if (!layout.placer.place(rocks, {-6.0f, 6.0f}, {-5.5f, 3.0f}, size * 1.1f, &at)) continue;
    float grey = static_cast<float>(rocks.range(0.38, 0.52));
    MeshData rock;
    add_rock(rock, rocks, glm::vec3(grey, grey * 0.96f, grey * 0.9f));
    bake_transform(rock, placed(sand, at, size * 0.2f, static_cast<float>(rocks.range(0, 6.28)),
                                glm::vec3(size * static_cast<float>(rocks.range(0.9, 1.3)),
                                          size * 0.65f, size)));
    layout.add_static(std::move(rock));
  }
}

void place_corals(Layout& layout) {
  const SandField& sand = layout.sand;
  Random corals = layout.random.fork(3);
  const glm::vec3 coral_colors[] = {
      {0.92f, 0.36f, 0.38f}, {0.95f, 0.52f, 0.22f}, {0.62f, 0.32f, 0.72f}, {0.95f, 0.62f, 0.62f}};
  for (int i = 0; i < 4; ++i) {
    glm::vec2 at;
    if (!layout.placer.place(corals, {-4.5f, 4.5f}, {-5.0f, -2.0f}, 0.9f, &at)) continue;
    MeshData coral;
    add_coral(coral, corals, coral_colors[i % 4]);
    float scale = static_cast<float>(corals.range(1.5, 2.3));
    bake_transform(
        coral, placed(sand, at, 0.0f, static_cast<float>(corals.range(0, 6.28)), glm::vec3(scale)));
    layout.add_static(std::move(coral));
  }
}

void place_shells(Layout& layout) {
  const SandField& sand = layout.sand;
  Random shells = layout.random.fork(4);
  const glm::vec3 shell_colors[] = {{0.95f, 0.86f, 0.72f}, {0.96f, 0.72f, 0.66f}};
  for (int i = 0; i < 5; ++i) {
    glm::vec2 at;
    float size = static_cast<float>(shells.range(0.2, 0.3));
    if (!layout.placer.place(shells, {-3.5f, 3.5f}, {1.5f, 4.5f}, size, &at)) continue;
    MeshData shell;
    add_shell(shell, shell_colors[i % 2]);
    bake_transform(
        shell, placed(sand, at, 0.01f, static_cast<float>(shells.range(0, 6.28)), glm::vec3(size)));
    layout.add_static(std::move(shell));
  }
}

void place_starfish(Layout& layout) {
  const SandField& sand = layout.sand;
  Random stars = layout.random.fork(5);
  for (int i = 0; i < 3; ++i) {
    glm::vec2 at;
    float size = static_cast<float>(stars.range(0.3, 0.42));
    if (!layout.placer.place(stars, {-3.5f, 3.5f}, {0.8f, 4.0f}, size, &at)) continue;
    MeshData star;
    add_starfish(star, i == 1 ? glm::vec3(0.85f, 0.25f, 0.3f) : glm::vec3(0.98f, 0.5f, 0.18f));
    bake_transform(
        star, placed(sand, at, 0.02f, static_cast<float>(stars.range(0, 6.28)), glm::vec3(size)));
    layout.add_static(std::move(star));
  }
}

// One seaweed cluster at `at`: 3-6 blades rooted in the sand, swaying (animated).
AnimatedObject seaweed_cluster(Random& weeds, const SandField& sand, glm::vec2 at,
                               uint32_t object_id) {
  std::vector<Blade> blades;
  int count = weeds.integer(3, 6);
  float tallest = 0.0f;
  for (int b = 0; b < count; ++b) {
    Blade blade;
    float dx = static_cast<float>(weeds.range(-0.25, 0.25));
    float dz = static_cast<float>(weeds.range(-0.25, 0.25));
    blade.root = {at.x + dx, sand.height(at.x + dx, at.y + dz) - 0.05f, at.y + dz};
    blade.height = static_cast<float>(weeds.range(1.2, 2.6));
    blade.width = static_cast<float>(weeds.range(0.12, 0.2));
    blade.facing = static_cast<float>(weeds.range(0, 3.14));
    blade.phase = static_cast<float>(weeds.range(0, 6.28));
    float bend_angle = static_cast<float>(weeds.range(0, 6.28));
    blade.bend = {std::cos(bend_angle), std::sin(bend_angle)};
    tallest = std::max(tallest, blade.height);
    blades.push_back(blade);
  }
  glm::vec3 green(static_cast<float>(weeds.range(0.15, 0.3)),
                  static_cast<float>(weeds.range(0.5, 0.62)),
                  static_cast<float>(weeds.range(0.2, 0.3)));
  AnimatedObject object;
  object.object_id = object_id;
  const float base_amplitude = 0.25f;
  float pad = base_amplitude * static_cast<float>(kMaxSway) + 0.5f;
  object.bounds_min = {at.x - pad, sand.height(at.x, at.y) - 0.5f, at.y - pad};
  object.bounds_max = {at.x + pad, sand.height(at.x, at.y) + tallest + 0.1f, at.y + pad};
  object.build = [blades, green, base_amplitude](double time, const AnimationSettings& settings,
                                                 MeshData& mesh) {
    for (const Blade& b : blades) {
      float amplitude = base_amplitude * static_cast<float>(settings.sway) * (b.height / 2.0f);
      float phase = b.phase + 1.3f * static_cast<float>(time);
      add_seaweed_blade(mesh, b.root, b.height, b.width, b.facing, b.bend, amplitude, phase, green);
    }
  };
  return object;
}

void place_seaweed(Layout& layout) {
  Random weeds = layout.random.fork(6);
  for (int i = 0; i < 5; ++i) {
    glm::vec2 at;
    if (!layout.placer.place(weeds, {-6.0f, 6.0f}, {-5.5f, 0.5f}, 0.5f, &at)) continue;
    layout.preset.animated.push_back(seaweed_cluster(weeds, layout.sand, at, layout.next_id++));
  }
}

// The fish, last so its id does not depend on how many static objects found a place; its
// loop is kept free of tall things.
void place_fish(Layout& layout) {
  const glm::vec3 fish_centre(0.6f, 1.9f, -0.8f);
  const float fish_radius = 2.2f;
  AnimatedObject fish;
  fish.object_id = layout.next_id++;
  fish.bounds_min = fish_centre - glm::vec3(fish_radius + 0.8f, 0.6f, fish_radius + 0.8f);
  fish.bounds_max = fish_centre + glm::vec3(fish_radius + 0.8f, 0.6f, fish_radius + 0.8f);
  fish.build = [fish_centre, fish_radius](double time, const AnimationSettings& settings,
                                          MeshData& mesh) {
    add_fish(mesh, time, 0.07f, glm::vec3(1.0f, 0.62f, 0.12f), glm::vec3(0.95f, 0.32f, 0.12f));
    float angle = static_cast<float>(settings.fish_speed * time);
    glm::vec3 at =
        fish_centre + glm::vec3(fish_radius * std::cos(angle), 0.25f * std::sin(2.0f * angle),
                                fish_radius * std::sin(angle));
    // Swimming counter-clockwise seen from above, the fish's +x follows the loop's tangent.
    glm::vec3 tangent(-std::sin(angle), 0.0f, std::cos(angle));
    float yaw = std::atan2(-tangent.z, tangent.x);
    glm::mat4 m = glm::translate(glm::mat4(1.0f), at);
    m = glm::rotate(m, yaw, glm::vec3(0, 1, 0));
    mesh.model = glm::scale(m, glm::vec3(1.1f));
  };
  layout.preset.animated.push_back(std::move(fish));
}

// The scene's objects in the order they are placed (and numbered): a table, so adding a kind
// is one line. The order is part of the preset (ids, and which places are still free).
constexpr void (*kPlacements[])(Layout&) = {
    place_pots, place_rocks, place_corals, place_shells, place_starfish, place_seaweed, place_fish};

}  // namespace

Preset make_underwater(uint64_t seed, double detail) {
  Preset preset;
  Random random(seed);
  SandField sand(seed);
  Placer placer;
  Layout layout{preset, random, sand, placer};
  layout.add_static(make_sand(sand, detail));
  for (auto place : kPlacements) place(layout);
  return preset;
}

}  // namespace scene
