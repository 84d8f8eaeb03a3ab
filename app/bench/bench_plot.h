// The plot of `aquarelle bench`, drawn with PLplot: small multiples, one panel per node type
// (its sweeps as curves of one colour each), time (x) against mean absolute error (y) on log
// axes with decade tick labels, every measured point hollow and the Pareto points (no other
// point of the sweep is both faster and more exact) filled and joined. Exact points (error 0)
// sit on the panel's bottom edge, labelled "exact". PNG, SVG or PDF by the file's extension.
#pragma once

#include <aquarelle/core/result.h>

#include <nlohmann/json.hpp>

#include <string>
#include <vector>

#include "bench_sweep.h"

namespace aq::app {

// Indices of the Pareto points of `sweep` (by time_ms.median and error.mean_abs), fastest
// first: each is more exact than every faster point.
std::vector<size_t> pareto_points(const Sweep& sweep);

Status write_plot(const std::vector<Sweep>& sweeps, const std::string& title,
                  const std::string& path);

// The sweeps of a report written by `aquarelle bench --json` (series, node, points with
// time_ms.median and mean_abs), so a plot can be redrawn without measuring again.
Result<std::vector<Sweep>> sweeps_from_report(const nlohmann::json& report);

}  // namespace aq::app
