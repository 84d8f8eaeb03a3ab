// The seed-001 sea floor (Coleman & Dodson) as an `object` shape: a grid over the unit square
// whose heights sum two Perlin frequencies, large swells and small bumps, plus a rock cliff
// rising along the back (-z) edge; uvs are the x-z position, so a sand texture tiles with the
// floor (the g-buffer samples it mipmapped and repeating). README, "terrain".
#pragma once

#include "mesh_data.h"
#include "perlin.h"

#include <cstdint>
#include <string>

namespace scene {

struct TerrainShape {
  double swell = 0.08;            // amplitude of the swells, object units
  double swell_frequency = 3.0;   // noise cells per object unit
  double bumps = 0.012;           // amplitude of the bumps
  double bumps_frequency = 24.0;  // noise cells per object unit
  double cliff = 0.0;             // height of the cliff along the -z edge (0: none)
  int cells = 128;                // grid cells per side
  double uv_repeat = 8.0;         // texture repeats across the square
};

// Empty, or what is wrong (a parameter that is not a finite number, or out of range), naming it.
std::string terrain_problem(const TerrainShape& shape);

// The noise fields of a seed: swells from `seed`, bumps (and the cliff's line) from a second
// stream, so the two frequencies are independent.
struct TerrainNoise {
  explicit TerrainNoise(uint64_t seed) : swell(seed), bumps(seed ^ 0x9e3779b97f4a7c15ull) {}
  Perlin2 swell, bumps;
};

// Height at (x, z), the unit square being [-0.5, 0.5]²:
//   h = swell · P1(fs x, fs z) + bumps · P2(fb x, fb z) + cliff · c(x, z)
//   c = smoothstep(0.28, 0.38, w) · smoothstep(0.3, 0.1, x),  w = -z + 0.05 · P2(5 x + 11.5, 0.5)
//   (the foot of the cliff wavers along x; the cliff ends towards +x)
double terrain_height(const TerrainShape& shape, const TerrainNoise& noise, double x, double z);

// How much of (x, z) is cliff rather than floor, 0..1 (its colour: rock against sand).
double terrain_cliff_weight(const TerrainShape& shape, const TerrainNoise& noise, double x,
                            double z);

// Appends the grid: (cells + 1)² vertices at x = -0.5 + i / cells, z = 0.5 - j / cells, each
// cell split along its (i, j)-(i+1, j+1) diagonal; normals from central differences of the
// height; uvs (x + 0.5, 0.5 - z) · uv_repeat; sand or rock colour by the cliff weight.
// A shape with a problem (terrain_problem) gives a flat grid.
void make_terrain(const TerrainShape& shape, uint64_t seed, MeshData& mesh);

}  // namespace scene
