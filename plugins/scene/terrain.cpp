#include "terrain.h"

#include "mesh_data.h"

#include <glm/glm.hpp>

#include <algorithm>
#include <cmath>

namespace scene {

namespace {

double smoothstep(double lo, double hi, double x) {
  const double t = std::clamp((x - lo) / (hi - lo), 0.0, 1.0);
  return t * t * (3.0 - 2.0 * t);
}

}  // namespace

std::string terrain_problem(const TerrainShape& shape) {
  const struct {
    const char* name;
    double value;
  } values[] = {{"terrain_swell", shape.swell}, {"terrain_swell_frequency", shape.swell_frequency},
                {"terrain_bumps", shape.bumps}, {"terrain_bumps_frequency", shape.bumps_frequency},
                {"terrain_cliff", shape.cliff}, {"terrain_uv_repeat", shape.uv_repeat}};
  for (const auto& v : values) {
    if (!std::isfinite(v.value)) {
      return std::string("parameter '") + v.name +
             "' is not a finite number; give a number (the terrain is flat until then)";
    }
  }
  if (shape.cells < 1 || shape.cells > 1024) return "the terrain grid must have 1 to 1024 cells";
  return "";
}

double terrain_cliff_weight(const TerrainShape& shape, const TerrainNoise& noise, double x,
                            double z) {
  if (shape.cliff == 0.0) return 0.0;
  const double w = -z + 0.05 * noise.bumps(5.0 * x + 11.5, 0.5);
  // Along the back edge from the left, ending at about x = 0.2 (a cliff, not a rim round the
  // whole floor).
  return smoothstep(0.28, 0.38, w) * smoothstep(0.3, 0.1, x);
}

double terrain_height(const TerrainShape& shape, const TerrainNoise& noise, double x, double z) {
  return shape.swell * noise.swell(shape.swell_frequency * x, shape.swell_frequency * z) +
         shape.bumps * noise.bumps(shape.bumps_frequency * x, shape.bumps_frequency * z) +
         shape.cliff * terrain_cliff_weight(shape, noise, x, z);
}

void make_terrain(const TerrainShape& asked, uint64_t seed, MeshData& mesh) {
  TerrainShape shape = asked;
  if (!terrain_problem(shape).empty()) {
    shape = TerrainShape{};
    shape.swell = shape.bumps = shape.cliff = 0.0;
  }
  const TerrainNoise noise(seed);
  const int n = shape.cells;
  const double step = 1.0 / n;
  const glm::vec3 sand(0.78f, 0.70f, 0.52f), rock(0.36f, 0.34f, 0.33f);
  MeshBuilder builder(mesh);
  const uint32_t first = mesh.vertex_count();
  for (int j = 0; j <= n; ++j) {
    for (int i = 0; i <= n; ++i) {
      const double x = -0.5 + i * step, z = 0.5 - j * step;
      const double h = terrain_height(shape, noise, x, z);
      const double dx = terrain_height(shape, noise, x + 0.5 * step, z) -
                        terrain_height(shape, noise, x - 0.5 * step, z);
      const double dz = terrain_height(shape, noise, x, z + 0.5 * step) -
                        terrain_height(shape, noise, x, z - 0.5 * step);
      const glm::vec3 normal = glm::normalize(glm::vec3(-dx / step, 1.0, -dz / step));
      const float rocky = static_cast<float>(terrain_cliff_weight(shape, noise, x, z));
      builder.vertex(glm::vec3(x, h, z), normal, glm::mix(sand, rock, rocky));
      mesh.uvs.insert(mesh.uvs.end(), {static_cast<float>((x + 0.5) * shape.uv_repeat),
                                       static_cast<float>((0.5 - z) * shape.uv_repeat)});
    }
  }
  const auto at = [&](int i, int j) { return first + static_cast<uint32_t>(j * (n + 1) + i); };
  for (int j = 0; j < n; ++j) {
    for (int i = 0; i < n; ++i) {
      builder.triangle(at(i, j), at(i + 1, j), at(i + 1, j + 1));
      builder.triangle(at(i, j), at(i + 1, j + 1), at(i, j + 1));
    }
  }
}

}  // namespace scene
