// What `aquarelle bench` found, and its three renderings: the text table, the JSON document
// (`--json`) and the CSV of every measurement (`--csv`).
#pragma once

#include <aquarelle/core/graph.h>
#include <aquarelle/core/registry.h>
#include <aquarelle/core/result.h>

#include <nlohmann/json.hpp>

#include <cstdio>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "bench_copy_pass.h"
#include "bench_node_error.h"
#include "bench_pipeline.h"
#include "bench_sweep.h"

namespace aq::app {

struct BenchReport {
  std::string graph;
  std::string gl;  // the context's description
  int width = 0;
  int height = 0;
  std::string precision;
  std::string quality;  // the preset timed (settings.quality, or --quality)
  int frames = 0;
  int warmup = 0;
  CopyPassTiming copy_pass;
  PipelineTiming every_node_runs;  // outputs not kept: every node runs every frame
  PipelineTiming cached;           // outputs kept: unchanged (static) nodes reused
  // By node id: the nodes that run an approximation, against their exact setting.
  std::map<std::string, NodeError> node_errors;
  bool cpu_references = false;
  std::vector<Sweep> sweeps;
  // --baseline: that graph's path and the two graphs' frames timed alternately in this run.
  std::string baseline_graph;
  std::optional<SideBySide> baseline;

  // The cached pipeline's median frame time over the copy pass's median (both wall
  // time).
  double copy_passes_per_frame() const;
  double copy_passes_per_frame_every_node_runs() const;
};

nlohmann::json report_json(const BenchReport& report);
void print_report(const BenchReport& report, std::FILE* out);
// One row per measurement (copy pass, node timings of both modes, sweep points).
Status write_report_csv(const BenchReport& report, const std::string& path);

// Before anything is measured: --csv and --plot (either may be empty) may be written, i.e.
// neither is the graph, a file it reads, --plot-from's report, the other one or a special file
// (aq::check_may_write). `graph` is null for --plot-from.
Status check_bench_outputs(const Graph* graph, const Registry& registry, const std::string& csv,
                           const std::string& plot, const std::string& plot_from);

// A saved `--json` report, for --plot-from: a regular file (a FIFO would block, a folder
// throws) of at most 64 MiB, parsed as JSON; errors name the file.
Result<nlohmann::json> read_report_file(const std::string& path);

}  // namespace aq::app
