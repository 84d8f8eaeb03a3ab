// The converged CPU reference of the `caustics` node: the caustic texture as the exact
// box-filtered flux of the refracted light per texel, in double precision, and an estimate of
// its own error from a sequence of grids (Richardson extrapolation with a fitted order).
//
// Light falling straight down on the tile [0,1)^2 carries flux dA through every surface
// element dA. The refraction map F (caustics_reference.h: floor_displacement) moves it to the
// floor; the light a texel T of side 1/n receives, divided by the texel's area, is
//
//     E(T) = n^2 · |F^-1(T)|                 (the area of its preimage, counted with folds)
//
// which is finite everywhere (the caustic's 1/sqrt singularities are integrable), exactly 1
// for flat water and has mean exactly 1 over the tile. On a grid of m x m cells split into
// 2 m^2 triangles, F is replaced by its linear interpolant on each triangle; a triangle's flux
// (its original area 1/(2 m^2)) is shared among the texels by the exact area of overlap of
// the refracted triangle with each texel (polygon clipping), wrapped around the tile. A
// folded triangle (negative refracted area) is clipped like any other: its flux stays
// positive; a degenerate one (zero refracted area) gives its flux to the texel holding it.
#pragma once

#include <aquarelle/core/image.h>

#include <vector>

#include "aquarelle/reference/caustics_reference.h"

namespace aq::reference {

// Box-filtered intensity per texel (row-major, row 0 at y = 0) of the piecewise-linear
// refraction map on a `grid` x `grid` grid, at params.resolution texels per side.
std::vector<double> caustic_flux_by_coverage(const CausticsParams& params, int grid);

// The same as an image: intensity in rgb, alpha 1.
ImageF caustics_by_coverage(const CausticsParams& params, int grid);
ImageF to_caustic_image(const std::vector<double>& texels, int resolution);

// Differences between successive grids m, 2m, 4m, ... and what they say about the finest one.
struct CausticConvergence {
  std::vector<int> grids;              // the grids computed, coarsest first
  std::vector<double> rms_steps;       // RMS of (grid k+1) - (grid k), one per refinement
  std::vector<double> mean_abs_steps;  // mean abs of the same differences
  double order = 0.0;                  // fitted convergence order p (error ~ grid^-p)
  double rms_error = 0.0;              // Richardson estimate of the finest grid's RMS error
  double mean_abs_error = 0.0;         // the same for the mean abs error
  std::vector<double> texels;          // the finest grid's texture (the reference)
};

// Computes the flux at `levels` grids ending at `finest_grid` (each half the next), fits the
// order from the last two refinements, p = log2(step_{k-1} / step_k), and estimates the
// finest grid's error by Richardson: step_last / (2^p - 1). Needs levels >= 3.
CausticConvergence converge_caustic_flux(const CausticsParams& params, int finest_grid,
                                         int levels = 3);

}  // namespace aq::reference
