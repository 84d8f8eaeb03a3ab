// Speed-against-error sweeps of `aquarelle bench`. A sweep is one curve of the plot: one node
// type (or the whole pipeline) measured at several quality settings against one reference.
//
// Four kinds of reference, named in every report:
//   cpu_reference        the node alone on a fixed test input against the double-precision CPU
//                        implementation in reference/ (written from the maths);
//   highest_quality      where no CPU reference exists: the graph's output with the node at the
//                        highest quality of the sweep, in float precision;
//   analytic_reference   known exact values (normal smoothing: the sphere a bumpy mesh stands for);
//   equivalence_reference  a configuration the swept one must equal exactly (swim_forward: the
//                        same body built along +x);
//   pipeline_reference   the whole graph at quality `final`, float precision, exact blur taps
//                        and a converged caustic grid.
#pragma once

#include <aquarelle/core/gl_context.h>
#include <aquarelle/core/graph.h>
#include <aquarelle/core/registry.h>
#include <aquarelle/core/result.h>

#include <nlohmann/json.hpp>

#include <set>
#include <string>
#include <vector>

#include "bench_measure.h"
#include "bench_stats.h"

namespace aq::app {

struct SweepPoint {
  std::string setting;                               // e.g. "grid=64" or "quality=draft"
  nlohmann::json params = nlohmann::json::object();  // the parameter values of this point
  std::string precision;
  Spread time_ms;  // the node's synced wall time, or the frame time for pipeline sweeps
  Spread gpu_ms;   // the node's GL_TIMESTAMP time (node sweeps; llvmpipe underestimates it)
  ErrorStats error;
  bool is_reference = false;  // this point re-renders the reference configuration
};

struct Sweep {
  std::string series;        // curve label, e.g. "blur sigma=4"
  std::string node_type;     // "pipeline" for preset sweeps
  std::string kind;          // cpu_reference | highest_quality | pipeline_reference
  std::string reference;     // what the reference is, in words
  std::string time_measure;  // "node wall" or "frame wall"
  std::string note;          // anything the reader must know (e.g. the reference's own error)
  double reference_ms = 0;   // time the reference took to compute (CPU references)
  std::vector<SweepPoint> points;
};

struct SweepPlan {
  int width = 256;
  int height = 144;
  int frames = 3;
  int warmup = 1;
  // Node types whose sweeps to run; empty = every type present in the graph.
  std::set<std::string> node_types;
  bool pipeline = true;  // the quality-preset sweep of the whole graph
};

// True when this build links the CPU references (reference/, AQUARELLE_BUILD_REFERENCES=ON).
bool have_cpu_references();

// Sweeps of single nodes on fixed test inputs against the CPU references. Types without a CPU
// reference are skipped; without references in the build, returns no sweep.
Result<std::vector<Sweep>> run_reference_sweeps(GlContext& context, const Registry& registry,
                                                const Graph& graph, const SweepPlan& plan,
                                                const std::set<std::string>& types);

// Sweeps of quality parameters that have no CPU reference, measured at the graph's output, and
// (plan.pipeline) the quality-preset sweep of the whole graph.
Result<std::vector<Sweep>> run_graph_sweeps(GlContext& context, const Registry& registry,
                                            const Graph& graph, const SweepPlan& plan,
                                            const std::set<std::string>& types);

// The scene node's normal smoothing at several iteration counts, CPU-timed, against the
// analytic normals of the shape a bumpy low-poly test mesh stands for (bench_smoothing_sweep.cpp).
// `graph_iterations` (the graph's setting) is added to the counts swept.
Result<Sweep> smoothing_sweep(const SweepPlan& plan, int graph_iterations);

// The layered watercolor's sweeps (id count and abstraction sigma against reference::layered)
// and the pigment colour chart (rgb, cmyk, Kubelka–Munk against reference::pigment_mix), when
// `types` holds `layered` or `pigment_mix` (bench_layered_sweeps.cpp).
Result<std::vector<Sweep>> run_layered_sweeps(GlContext& context, const Registry& registry,
                                              const Graph& graph, const SweepPlan& plan,
                                              const std::set<std::string>& types);

// Seed 001's deep-ocean parts (bench_deep_ocean_sweeps.cpp): `environment` against
// reference::environment, caustics `shift` and `blend_interval` against the flux reference (both
// need the CPU references), the terrain's grid (`object` terrain_cells, when the graph has a
// terrain) and `swim_forward` (when an object swims), when `types` holds the node type.
Result<std::vector<Sweep>> run_deep_ocean_sweeps(GlContext& context, const Registry& registry,
                                                 const Graph& graph, const SweepPlan& plan,
                                                 const std::set<std::string>& types);

}  // namespace aq::app
