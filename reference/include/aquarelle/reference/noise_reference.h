// CPU reference of the shared procedural noise (nodes/shaders/noise.glsl) in double precision,
// for the tests of the noise, paper and caustics nodes and for `aquarelle bench`.
//
// The lattice values are defined by 32-bit integer hashes (PCG2D/PCG3D, Jarzynski & Olano
// 2020), reproduced bit for bit here; everything after the hash (fade curves, interpolation,
// Box-Muller, distances) is evaluated in double precision from the definitions.
#pragma once

#include <array>
#include <cstdint>

namespace aq::reference::noise {

struct Vec2 {
  double x = 0.0;
  double y = 0.0;
};
struct Vec3 {
  double x = 0.0;
  double y = 0.0;
  double z = 0.0;
};

std::array<uint32_t, 2> pcg2d(uint32_t x, uint32_t y);
std::array<uint32_t, 3> pcg3d(uint32_t x, uint32_t y, uint32_t z);

// The top 24 bits of a hash as a number in [0,1).
double unit_from_hash(uint32_t h);

// floor(p) wrapped into [0, round(period)) when round(period) > 0.
int64_t wrap_cell(int64_t cell, double period);

double hash12(Vec2 p);

// Gradient noise, range [-1,1] (2D) and about [-1,1] (3D); period 0 = not periodic.
double perlin2(Vec2 p, Vec2 period, uint32_t seed = 0);

struct ValueAndGradient {
  double value = 0.0;
  Vec3 gradient;
};
ValueAndGradient perlin3_with_gradient(Vec3 p, Vec3 period);
double perlin3(Vec3 p, Vec3 period);

// Normalised fractal sum of perlin2 octaves (see noise.glsl).
double fbm2(Vec2 p, Vec2 period, int octaves, uint32_t seed = 0);

// Standard-normal sample of the cell floor(cell) for a seed given as a float (its bits count).
double gaussian_noise(Vec2 cell, float seed);

// Exact Worley F1 distance.
double worley2(Vec2 p, Vec2 period, uint32_t seed = 0);

// aq_fbm3 (seed 002): `octaves` non-periodic perlin3 layers, frequency 2^k, amplitude 2^-k,
// octave k shifted by k·(17.13, 31.71, 47.37), divided by the total amplitude.
double fbm3(Vec3 p, int octaves);

// aq_perlin3_bent / aq_fbm3_bent (seed 002's cubism): perlin3 (not periodic) blended with
// smoothstep(bend/2, 1 − bend/2, t) per axis instead of the quintic fade; bend in (0, 0.95].
double perlin3_bent(Vec3 p, double bend);
double fbm3_bent(Vec3 p, int octaves, double bend);

}  // namespace aq::reference::noise
