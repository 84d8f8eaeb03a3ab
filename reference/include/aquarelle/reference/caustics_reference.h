// CPU reference of the `caustics` node (Stam's periodic caustic texture by grid refraction) in
// double precision, written from the maths in plugins/caustics/README.md, for the tests and
// `aquarelle bench`.
//
// Units: the tile is the unit square; heights, depth and displacements are in tile widths.
#pragma once

#include <aquarelle/core/image.h>

namespace aq::reference {

struct CausticsParams {
  int grid = 256;               // grid cells per tile side
  int resolution = 256;         // texture pixels per tile side
  double depth = 0.5;           // floor below the mean water level
  double amplitude = 0.02;      // height of the normalised 3-octave noise
  int wave_scale = 4;           // noise cells per tile of the first octave
  double speed = 0.5;           // noise cells per second along the time axis
  double eta = 1.0 / 1.333;     // refraction ratio n_air / n_water
  double max_intensity = 32.0;  // per-triangle intensity clamp
  double time = 0.0;            // seconds
};

struct Displacement {
  double x = 0.0;
  double y = 0.0;
};

// Water height at tile position (x, y) and its analytic gradient.
struct WaterSample {
  double height = 0.0;
  double dhdx = 0.0;
  double dhdy = 0.0;
};
WaterSample water_surface(double x, double y, const CausticsParams& params);

// Where the vertical light ray through (x, y) meets the floor, minus (x, y).
Displacement floor_displacement(double x, double y, const CausticsParams& params);

// Grid refraction with `grid` cells per side: every refracted triangle adds
// min(original area / |refracted area|, max_intensity) to the pixel centres it covers (wrapped
// around the tile). With grid >> resolution this converges to the point-sampled caustic
// intensity sum over preimages of min(1/|J|, max_intensity). Intensity in rgb, alpha 1.
ImageF caustics_by_grid(const CausticsParams& params, int grid);

// Photon splatting: samples_per_side^2 stratified photons, each carrying 1/samples^2 of the
// tile's light, deposited into the pixel they land in (box filter, wrapped). An independent
// estimate of the pixel-averaged intensity; the mean is exactly 1 by construction.
ImageF caustics_by_photons(const CausticsParams& params, int samples_per_side);

}  // namespace aq::reference
