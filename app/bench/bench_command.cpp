// `aquarelle bench`: speed against error. Times a full-screen copy pass as the yardstick, then
// every node of a graph (every node running, and static nodes cached), then sweeps the quality
// settings of the nodes against references and writes a table, JSON, CSV and a plot.
#include <aquarelle/core/evaluator.h>

#include <cstdio>
#include <fstream>
#include <set>

#include "bench_copy_pass.h"
#include "bench_pipeline.h"
#include "bench_plot.h"
#include "bench_report.h"
#include "bench_sweep.h"
#include "commands.h"
#include "session.h"

namespace aq::app {

namespace {

constexpr const char* kBenchHelp =
    R"(usage: aquarelle bench [GRAPH] [options]

Measures speed against error. First times a full-screen copy pass of the graph's size and
format (the yardstick), then each node of GRAPH over N frames after warm-up (median GPU and CPU
time with their spread), once with every node running each frame and once with static nodes
cached, and reports the frame cost as copy passes per frame. Then sweeps the quality settings
of the graph's nodes (blur method and taps, caustic grid, erode/dilate size and footprint,
shadow map size and its auto size, caustic texture size and its footprint size, normal
smoothing iterations, half or float precision) measuring time and error (max abs, mean abs,
PSNR) against a reference: the double-precision CPU references of reference/ where they
exist, exact values where they are known (smoothing: the sphere a bumpy mesh stands for), else
the node at its highest quality in float; and the graph's quality presets against a float
reference render.

  GRAPH                   graph file (default: graphs/underwater.json)
  --size WxH              render size (default 256x144; the issue's figure is 1280x720)
  --frames N              timed frames per measurement (default 5; sweeps use min(N, 3))
  --warmup N              untimed frames before timing (default 2)
  --node TYPE             sweep only this node type (repeatable); a type not in the graph is
                          swept alone on the fixed test input when it has a CPU reference
  --no-sweep              timing only, no sweeps
  --pipeline-only         of the sweeps, only the quality presets of the whole graph
  --precision half|float  working precision (default: the graph's settings.precision)
  --quality draft|preview|final
                          quality preset to time (default: the graph's settings.quality);
                          the preset sweep still measures all three
  --set NODE.PARAM=VALUE  override a parameter before timing (repeatable; VALUE as JSON), e.g.
                          to time a graph with one optimisation switched off
  --csv OUT.csv           write every measurement as CSV
  --plot OUT.png          plot time against mean abs error: a panel per node, a curve per
                          sweep, the Pareto front marked (PLplot; .png, .svg or .pdf)
  --plot-from REPORT.json redraw --plot from a saved `--json` report, without measuring
  --json                  print the report as JSON instead of the table
  --gl auto|egl|osmesa    GL backend (default auto)
  --gl-device D           EGL device: auto (a GPU when EGL lists one, else llvmpipe),
                          software, or an index; a bad one lists the devices
  -q, --quiet             no progress messages on stderr

Exit codes: 0 ok, 1 bad input (graph, arguments, files), 2 no usable GL or plugins.
)";

struct Arguments {
  std::string graph_path = "graphs/underwater.json";
  std::string size = "256x144";
  int frames = 5;
  int warmup = 2;
  std::set<std::string> node_types;
  bool sweep = true;
  bool pipeline_only = false;
  std::string precision;
  std::string quality;
  std::vector<std::string> sets;
  std::string csv;
  std::string plot;
  std::string plot_from;
  bool json = false;
  std::string gl = "auto";
  std::string gl_device = "auto";
  bool quiet = false;
};

// Parses the arguments; returns an exit code when the command should stop (help, error).
std::optional<int> parse_arguments(int argc, char** argv, Arguments* args) {
  bool graph_given = false;
  for (int i = 1; i < argc; ++i) {
    std::string arg = argv[i];
    auto value = [&]() -> std::optional<std::string> {
      auto v = option_value(argc, argv, &i);
      if (!v.ok()) {
        std::fprintf(stderr, "aquarelle bench: %s\n", v.message().c_str());
        return std::nullopt;
      }
      return *v;
    };
    auto count = [&](const char* name, int minimum, int* out) -> bool {
      auto v = value();
      if (!v) return false;
      try {
        size_t used = 0;
        int n = std::stoi(*v, &used);
        if (used == v->size() && n >= minimum && n <= 100000) {
          *out = n;
          return true;
        }
      } catch (const std::exception&) {
      }
      std::fprintf(stderr, "aquarelle bench: %s '%s': expected a whole number >= %d\n", name,
                   v->c_str(), minimum);
      return false;
    };
    if (arg == "--help" || arg == "-h") {
      std::fputs(kBenchHelp, stdout);
      return kExitOk;
    } else if (arg == "--size") {
      auto v = value();
      if (!v) return kExitBadInput;
      args->size = *v;
    } else if (arg == "--frames") {
      if (!count("--frames", 1, &args->frames)) return kExitBadInput;
    } else if (arg == "--warmup") {
      if (!count("--warmup", 0, &args->warmup)) return kExitBadInput;
    } else if (arg == "--node") {
      auto v = value();
      if (!v) return kExitBadInput;
      args->node_types.insert(*v);
    } else if (arg == "--no-sweep") {
      args->sweep = false;
    } else if (arg == "--pipeline-only") {
      args->pipeline_only = true;
    } else if (arg == "--precision") {
      auto v = value();
      if (!v) return kExitBadInput;
      if (*v != "half" && *v != "float") {
        std::fprintf(stderr, "aquarelle bench: --precision must be half or float\n");
        return kExitBadInput;
      }
      args->precision = *v;
    } else if (arg == "--quality") {
      auto v = value();
      if (!v) return kExitBadInput;
      if (*v != "draft" && *v != "preview" && *v != "final") {
        std::fprintf(stderr, "aquarelle bench: --quality '%s': must be draft, preview or final\n",
                     v->c_str());
        return kExitBadInput;
      }
      args->quality = *v;
    } else if (arg == "--set") {
      auto v = value();
      if (!v) return kExitBadInput;
      args->sets.push_back(*v);
    } else if (arg == "--csv") {
      auto v = value();
      if (!v) return kExitBadInput;
      args->csv = *v;
    } else if (arg == "--plot") {
      auto v = value();
      if (!v) return kExitBadInput;
      args->plot = *v;
    } else if (arg == "--plot-from") {
      auto v = value();
      if (!v) return kExitBadInput;
      args->plot_from = *v;
    } else if (arg == "--json") {
      args->json = true;
    } else if (arg == "--gl-device") {
      auto v = value();
      if (!v) return kExitBadInput;
      args->gl_device = *v;
    } else if (arg == "--gl") {
      auto v = value();
      if (!v) return kExitBadInput;
      args->gl = *v;
    } else if (arg == "-q" || arg == "--quiet") {
      args->quiet = true;
    } else if (!arg.empty() && arg[0] == '-') {
      std::fprintf(stderr, "aquarelle bench: unknown option '%s' (see --help)\n", arg.c_str());
      return kExitBadInput;
    } else if (!graph_given) {
      args->graph_path = arg;
      graph_given = true;
    } else {
      std::fprintf(stderr, "aquarelle bench: more than one graph given ('%s')\n", arg.c_str());
      return kExitBadInput;
    }
  }
  return std::nullopt;
}

void progress(const Arguments& args, const char* what) {
  if (!args.quiet) std::fprintf(stderr, "aquarelle bench: %s\n", what);
}

}  // namespace

// --plot-from: the plot of a saved report, nothing measured.
int replot(const Arguments& args) {
  if (args.plot.empty()) {
    std::fprintf(stderr, "aquarelle bench: --plot-from needs --plot OUT.png\n");
    return kExitBadInput;
  }
  if (auto s = check_bench_outputs(nullptr, Registry(), "", args.plot, args.plot_from); !s.ok()) {
    std::fprintf(stderr, "aquarelle bench: %s\n", s.message().c_str());
    return kExitBadInput;
  }
  auto read = read_report_file(args.plot_from);
  if (!read.ok()) {
    std::fprintf(stderr, "aquarelle bench: %s\n", read.message().c_str());
    return kExitBadInput;
  }
  const nlohmann::json& report = *read;
  auto sweeps = sweeps_from_report(report);
  if (!sweeps.ok()) {
    std::fprintf(stderr, "aquarelle bench: --plot-from %s: %s\n",
                 quote_for_message(args.plot_from).c_str(), sweeps.message().c_str());
    return kExitBadInput;
  }
  std::string title = report.value("graph", std::string());
  const auto size = report.value("size", nlohmann::json::array());
  if (size.size() == 2 && size[0].is_number() && size[1].is_number()) {
    title += " " + std::to_string(size[0].get<int>()) + "x" + std::to_string(size[1].get<int>());
  }
  title += " " + report.value("precision", std::string());
  if (auto s = write_plot(*sweeps, title, args.plot); !s.ok()) {
    std::fprintf(stderr, "aquarelle bench: --plot: %s\n", s.message().c_str());
    return kExitBadInput;
  }
  return kExitOk;
}

int run_bench(int argc, char** argv) {
  Arguments args;
  if (auto stop = parse_arguments(argc, argv, &args)) return *stop;
  if (!args.plot_from.empty()) return replot(args);

  if (auto device = check_gl_device(args.gl_device); !device.ok()) {
    std::fprintf(stderr, "aquarelle bench: --gl-device: %s\n", device.message().c_str());
    return kExitBadInput;
  }
  auto backend = parse_backend(args.gl);
  if (!backend.ok()) {
    std::fprintf(stderr, "aquarelle bench: --gl: %s\n", backend.message().c_str());
    return kExitBadInput;
  }
  auto plugins = load_plugins(args.quiet);
  if (!plugins.ok()) {
    std::fprintf(stderr, "aquarelle bench: %s\n", plugins.message().c_str());
    return kExitEnvironment;
  }
  const Registry& registry = (*plugins)->registry;
  for (const auto& type : args.node_types) {
    if (registry.find(type) == nullptr) {
      std::string names;
      for (const auto& name : registry.names()) names += (names.empty() ? "" : ", ") + name;
      std::fprintf(stderr, "aquarelle bench: --node '%s': no such node type (installed: %s)\n",
                   type.c_str(), names.c_str());
      return kExitBadInput;
    }
  }
  ReadResult read = read_graph_file(args.graph_path, registry);
  if (!read.ok()) {
    std::fprintf(stderr, "%s\n", format_problems(read.problems).c_str());
    return kExitBadInput;
  }
  Graph graph = std::move(read.graph);
  if (auto s = parse_size(args.size, &graph.settings.width, &graph.settings.height); !s.ok()) {
    std::fprintf(stderr, "aquarelle bench: %s\n", s.message().c_str());
    return kExitBadInput;
  }
  if (!args.precision.empty()) graph.settings.precision = args.precision;
  if (!args.quality.empty()) graph.settings.quality = args.quality;
  for (const auto& assignment : args.sets) {
    if (auto s = apply_setting(graph, registry, assignment); !s.ok()) {
      std::fprintf(stderr, "aquarelle bench: --set: %s\n", s.message().c_str());
      return kExitBadInput;
    }
  }
  if (auto s = check_bench_outputs(&graph, registry, args.csv, args.plot, ""); !s.ok()) {
    std::fprintf(stderr, "aquarelle bench: %s\n", s.message().c_str());
    return kExitBadInput;
  }

  auto context = create_headless_context(*backend, args.gl_device);
  if (!context.ok()) {
    std::fprintf(stderr, "aquarelle bench: %s\n", context.message().c_str());
    return kExitEnvironment;
  }
  (*context)->activate();

  BenchReport report;
  report.graph = args.graph_path;
  report.gl = (*context)->description();
  report.width = graph.settings.width;
  report.height = graph.settings.height;
  report.precision = graph.settings.precision;
  report.quality = graph.settings.quality;
  report.frames = args.frames;
  report.warmup = args.warmup;
  report.cpu_references = have_cpu_references();
  if (!args.quiet) std::fprintf(stderr, "aquarelle bench: %s\n", report.gl.c_str());

  progress(args, "timing a full-screen copy pass");
  const uint32_t format =
      graph.settings.precision == "float" ? AQ_FORMAT_RGBA32F : AQ_FORMAT_RGBA16F;
  auto copy_pass = CopyPass::create(report.width, report.height, format);
  if (!copy_pass.ok()) {
    std::fprintf(stderr, "aquarelle bench: %s\n", copy_pass.message().c_str());
    return kExitEnvironment;
  }
  // The yardstick: batches before the graph runs and between its frames, all in one median.
  std::vector<CopyPass::Sample> copies;
  for (int i = 0; i < args.warmup + 1 + args.frames; ++i) {
    CopyPass::Sample sample = copy_pass->run_batch();
    if (i > args.warmup) copies.push_back(sample);
  }

  progress(args, "timing the graph: every node running, and static nodes cached");
  TimingPlan timing_plan;
  timing_plan.frames = args.frames;
  timing_plan.warmup = std::max(args.warmup, 1);
  auto timings = time_pipeline(**context, registry, graph, timing_plan, *copy_pass);
  if (!timings.ok()) {
    std::fprintf(stderr, "aquarelle bench: %s: %s\n", args.graph_path.c_str(),
                 timings.message().c_str());
    return kExitBadInput;
  }
  report.every_node_runs = timings->every_node_runs;
  report.cached = timings->cached;
  copies.insert(copies.end(), timings->copy_samples.begin(), timings->copy_samples.end());
  std::vector<double> copy_wall, copy_timestamp;
  for (const auto& sample : copies) {
    copy_wall.push_back(sample.wall_ms);
    copy_timestamp.push_back(sample.timestamp_ms);
  }
  report.copy_pass = CopyPassTiming{summarize(copy_wall), summarize(copy_timestamp)};

  if (args.sweep) {
    SweepPlan plan;
    plan.width = report.width;
    plan.height = report.height;
    plan.frames = std::min(args.frames, 3);
    plan.warmup = 1;
    std::set<std::string> types = args.node_types;
    if (types.empty() && !args.pipeline_only) {
      for (const auto& [id, node] : graph.nodes) types.insert(node.type);
    }
    plan.pipeline = args.node_types.empty();
    progress(args, report.cpu_references ? "sweeping quality settings against CPU references"
                                         : "no CPU references in this build: accuracy sweeps "
                                           "skipped (reconfigure with "
                                           "-DAQUARELLE_BUILD_REFERENCES=ON)");
    auto reference_sweeps = run_reference_sweeps(**context, registry, graph, plan, types);
    if (!reference_sweeps.ok()) {
      std::fprintf(stderr, "aquarelle bench: %s\n", reference_sweeps.message().c_str());
      return kExitBadInput;
    }
    report.sweeps = *reference_sweeps;
    progress(args, "sweeping quality settings at the graph's output and its presets");
    auto graph_sweeps = run_graph_sweeps(**context, registry, graph, plan, types);
    if (!graph_sweeps.ok()) {
      std::fprintf(stderr, "aquarelle bench: %s\n", graph_sweeps.message().c_str());
      return kExitBadInput;
    }
    report.sweeps.insert(report.sweeps.end(), graph_sweeps->begin(), graph_sweeps->end());
    auto layered_sweeps = run_layered_sweeps(**context, registry, graph, plan, types);
    if (!layered_sweeps.ok()) {
      std::fprintf(stderr, "aquarelle bench: %s\n", layered_sweeps.message().c_str());
      return kExitBadInput;
    }
    report.sweeps.insert(report.sweeps.end(), layered_sweeps->begin(), layered_sweeps->end());
  }

  if (args.json) {
    std::printf("%s\n", report_json(report).dump(2).c_str());
  } else {
    print_report(report, stdout);
  }
  if (!args.csv.empty()) {
    if (auto s = write_report_csv(report, args.csv); !s.ok()) {
      std::fprintf(stderr, "aquarelle bench: --csv: %s\n", s.message().c_str());
      return kExitBadInput;
    }
  }
  if (!args.plot.empty()) {
    char title[160];
    std::snprintf(title, sizeof(title), "%s %dx%d %s", args.graph_path.c_str(), report.width,
                  report.height, report.precision.c_str());
    if (auto s = write_plot(report.sweeps, title, args.plot); !s.ok()) {
      std::fprintf(stderr, "aquarelle bench: --plot: %s\n", s.message().c_str());
      return kExitBadInput;
    }
  }
  return kExitOk;
}

}  // namespace aq::app
