// The plot of `aquarelle bench`: time (x, log) against mean absolute error (y, log), one curve
// per sweep, every measured point as a hollow marker and the Pareto points (no other point of
// the sweep is both faster and more exact) filled and joined. Drawn into an ImageF by the
// project itself (lines, markers, a 5x7 bitmap font) and written as PNG, so it needs nothing
// beyond image I/O.
#pragma once

#include <aquarelle/core/image.h>
#include <aquarelle/core/result.h>

#include <string>
#include <vector>

#include "bench_sweep.h"

namespace aq::app {

// Indices of the Pareto points of `sweep` (by time_ms.median and error.mean_abs), fastest
// first: each is more exact than every faster point.
std::vector<size_t> pareto_points(const Sweep& sweep);

// Exact points (error 0) are drawn on the bottom line of the plot, labelled "exact".
ImageF draw_plot(const std::vector<Sweep>& sweeps, const std::string& title);

Status write_plot(const std::vector<Sweep>& sweeps, const std::string& title,
                  const std::string& path);

}  // namespace aq::app
