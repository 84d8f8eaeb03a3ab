// `aquarelle bench`: speed against error. Times a full-screen copy pass as the yardstick, then
// every node of a graph (every node running, and static nodes cached), then sweeps the quality
// settings of the nodes against references and writes a table, JSON, CSV and a plot.
#include <aquarelle/core/evaluator.h>

#include <cstdio>
#include <fstream>
#include <memory>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "bench_copy_pass.h"
#include "bench_node_error.h"
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
cached, and reports the frame cost as copy passes per frame. Beside each node that runs an
approximation (cells, rays per block, linear taps, a coarse grid) the table gives its error:
its output against the same node at its exact setting on the same inputs. Then sweeps the quality settings
of the graph's nodes (blur method and taps, caustic grid, erode/dilate size and footprint,
shadow map size and its auto size, caustic texture size and its footprint size, normal
smoothing iterations, half or float precision) measuring time and error (max abs, mean abs,
PSNR) against a reference: the double-precision CPU references of reference/ where they
exist, exact values where they are known (smoothing: the sphere a bumpy mesh stands for), else
the node at its highest quality in float; and the graph's quality presets against a float
reference render. With --baseline, also times GRAPH's frames and another graph's alternately in
the same run and reports their ratio (on a shared machine, the figure to quote: two separate
runs see different loads).)";

struct Arguments {
  std::vector<std::string> graphs;
  std::string graph_path = "graphs/underwater.json";
  std::string size = "256x144";
  std::string frames_text = "5", warmup_text = "2";
  int frames = 5;
  int warmup = 2;
  std::vector<std::string> node_list;
  std::set<std::string> node_types;
  bool no_sweep = false;
  bool sweep = true;
  bool pipeline_only = false;
  std::string precision;
  std::string quality;
  std::vector<std::string> sets;
  std::string baseline;
  std::string csv;
  std::string plot;
  std::string plot_from;
  bool json = false;
  std::string gl = "auto";
  std::string gl_device = "auto";
  bool quiet = false;
};

void declare_options(CLI::App& command, Arguments& args) {
  command.add_option("GRAPH", args.graphs, "graph file (default: graphs/underwater.json)");
  command
      .add_option("--size", args.size,
                  "render size (default 256x144; the issue's figure is 1280x720)")
      ->type_name("WxH");
  command
      .add_option("--frames", args.frames_text,
                  "timed frames per measurement (default 5; sweeps use min(N, 3))")
      ->type_name("N");
  command.add_option("--warmup", args.warmup_text, "untimed frames before timing (default 2)")
      ->type_name("N");
  command
      .add_option("--node", args.node_list,
                  "sweep only this node type (repeatable); a type not in the graph is\n"
                  "swept alone on the fixed test input when it has a CPU reference")
      ->type_name("TYPE")
      ->allow_extra_args(false);
  command.add_flag("--no-sweep", args.no_sweep, "timing only, no sweeps");
  command.add_flag("--pipeline-only", args.pipeline_only,
                   "of the sweeps, only the quality presets of the whole graph");
  command
      .add_option("--precision", args.precision,
                  "working precision (default: the graph's settings.precision)")
      ->type_name("half|float");
  command
      .add_option("--quality", args.quality,
                  "quality preset to time (default: the graph's settings.quality);\n"
                  "the preset sweep still measures all three")
      ->type_name("draft|preview|final");
  command
      .add_option("--set", args.sets,
                  "override a parameter before timing (repeatable; VALUE as JSON), e.g.\n"
                  "to time a graph with one optimisation switched off")
      ->type_name("NODE.PARAM=VALUE")
      ->allow_extra_args(false);
  command
      .add_option("--baseline", args.baseline,
                  "also time this graph's frames alternately with GRAPH's (same --size,\n"
                  "--quality and --precision; --set applies to GRAPH only) and report\n"
                  "GRAPH's frame over the baseline's, e.g. graphs/underwater.json")
      ->type_name("GRAPH2");
  command.add_option("--csv", args.csv, "write every measurement as CSV")->type_name("OUT.csv");
  command
      .add_option("--plot", args.plot,
                  "plot time against mean abs error: a panel per node, a curve per\n"
                  "sweep, the Pareto front marked (PLplot; .png, .svg or .pdf)")
      ->type_name("OUT.png");
  command
      .add_option("--plot-from", args.plot_from,
                  "redraw --plot from a saved `--json` report, without measuring")
      ->type_name("REPORT.json");
  command.add_flag("--json", args.json, "print the report as JSON instead of the table");
  command.add_option("--gl", args.gl, "GL backend (default auto)")->type_name("auto|egl|osmesa");
  command
      .add_option("--gl-device", args.gl_device,
                  "EGL device: auto (a GPU when EGL lists one, else llvmpipe),\n"
                  "software, or an index; a bad one lists the devices")
      ->type_name("D");
  command.add_flag("-q,--quiet", args.quiet, "no progress messages on stderr");
}

// A whole number >= minimum (and <= 100000) for --frames and --warmup.
bool parse_count(const char* name, const std::string& text, int minimum, int* out) {
  try {
    size_t used = 0;
    int n = std::stoi(text, &used);
    if (used == text.size() && n >= minimum && n <= 100000) {
      *out = n;
      return true;
    }
  } catch (const std::exception&) {
  }
  std::fprintf(stderr, "aquarelle bench: %s %s: expected a whole number >= %d\n", name,
               quote_for_message(text).c_str(), minimum);
  return false;
}

// Checks and completes the parsed arguments; returns an exit code when the command should stop.
std::optional<int> check_arguments(Arguments* args) {
  if (args->graphs.size() > 1) {
    std::fprintf(stderr, "aquarelle bench: more than one graph given (%s)\n",
                 quote_for_message(args->graphs[1]).c_str());
    return kExitBadInput;
  }
  if (!args->graphs.empty()) args->graph_path = args->graphs[0];
  if (!parse_count("--frames", args->frames_text, 1, &args->frames)) return kExitBadInput;
  if (!parse_count("--warmup", args->warmup_text, 0, &args->warmup)) return kExitBadInput;
  if (!args->precision.empty() && args->precision != "half" && args->precision != "float") {
    std::fprintf(stderr, "aquarelle bench: --precision must be half or float\n");
    return kExitBadInput;
  }
  if (!args->quality.empty() && args->quality != "draft" && args->quality != "preview" &&
      args->quality != "final") {
    std::fprintf(stderr, "aquarelle bench: --quality %s: must be draft, preview or final\n",
                 quote_for_message(args->quality).c_str());
    return kExitBadInput;
  }
  args->node_types.insert(args->node_list.begin(), args->node_list.end());
  args->sweep = !args->no_sweep;
  return std::nullopt;
}

void progress(const Arguments& args, const char* what) {
  if (!args.quiet) std::fprintf(stderr, "aquarelle bench: %s\n", what);
}

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

int refuse(const std::string& message, int code = kExitBadInput) {
  std::fprintf(stderr, "aquarelle bench: %s\n", message.c_str());
  return code;
}

// The graph at `path` to time, with --size, --precision and --quality applied, and --set when
// `with_sets` (the baseline's node ids are its own); every --node type must be installed.
std::optional<int> load_graph(const Arguments& args, const Registry& registry,
                              const std::string& path, bool with_sets, Graph* graph) {
  for (const auto& type : args.node_types) {
    if (registry.find(type) == nullptr) {
      std::string names;
      for (const auto& name : registry.names()) names += (names.empty() ? "" : ", ") + name;
      return refuse("--node '" + type + "': no such node type (installed: " + names + ")");
    }
  }
  ReadResult read = read_graph_file(path, registry);
  if (!read.ok()) {
    std::fprintf(stderr, "%s%s\n", with_sets ? "" : "aquarelle bench: --baseline: ",
                 format_problems(read.problems).c_str());
    return kExitBadInput;
  }
  *graph = std::move(read.graph);
  if (auto s = parse_size(args.size, &graph->settings.width, &graph->settings.height); !s.ok())
    return refuse(s.message());
  if (!args.precision.empty()) graph->settings.precision = args.precision;
  if (!args.quality.empty()) graph->settings.quality = args.quality;
  if (!with_sets) return std::nullopt;
  for (const auto& assignment : args.sets) {
    if (auto s = apply_setting(*graph, registry, assignment); !s.ok())
      return refuse("--set: " + s.message());
  }
  return std::nullopt;
}

// The yardstick and the graph's timings: copy-pass batches before the graph runs and between
// its frames, all in one median; every node running, and static nodes cached.
std::optional<int> time_graph(const Arguments& args, GlContext& context, const Registry& registry,
                              const Graph& graph, const Graph* baseline, BenchReport* report) {
  progress(args, "timing a full-screen copy pass");
  const uint32_t format =
      graph.settings.precision == "float" ? AQ_FORMAT_RGBA32F : AQ_FORMAT_RGBA16F;
  auto copy_pass = CopyPass::create(report->width, report->height, format);
  if (!copy_pass.ok()) return refuse(copy_pass.message(), kExitEnvironment);
  std::vector<CopyPass::Sample> copies;
  for (int i = 0; i < args.warmup + 1 + args.frames; ++i) {
    CopyPass::Sample sample = copy_pass->run_batch();
    if (i > args.warmup) copies.push_back(sample);
  }
  if (auto s = check_bench_outputs(&graph, registry, args.csv, args.plot, ""); !s.ok()) {
    std::fprintf(stderr, "aquarelle bench: %s\n", s.message().c_str());
    return kExitBadInput;
  }

  progress(args, "timing the graph: every node running, and static nodes cached");
  TimingPlan timing_plan;
  timing_plan.frames = args.frames;
  timing_plan.warmup = std::max(args.warmup, 1);
  auto timings = time_pipeline(context, registry, graph, timing_plan, *copy_pass);
  if (!timings.ok()) return refuse(args.graph_path + ": " + timings.message());
  report->every_node_runs = timings->every_node_runs;
  report->cached = timings->cached;
  copies.insert(copies.end(), timings->copy_samples.begin(), timings->copy_samples.end());
  std::vector<double> copy_wall, copy_timestamp;
  for (const auto& sample : copies) {
    copy_wall.push_back(sample.wall_ms);
    copy_timestamp.push_back(sample.timestamp_ms);
  }
  report->copy_pass = CopyPassTiming{summarize(copy_wall), summarize(copy_timestamp)};
  if (baseline != nullptr) {
    progress(args, "timing the graph's frames and the baseline's, alternately");
    auto side_by_side = time_side_by_side(context, registry, graph, *baseline, timing_plan);
    if (!side_by_side.ok()) return refuse(args.graph_path + ": " + side_by_side.message());
    report->baseline_graph = args.baseline;
    report->baseline = *side_by_side;
  }
  progress(args, "measuring each approximating node against its exact setting");
  report->node_errors = node_errors(context, registry, graph);
  return std::nullopt;
}

// The quality sweeps: against the CPU references, at the graph's output and its presets, and
// the layered node's.
std::optional<int> sweep(const Arguments& args, GlContext& context, const Registry& registry,
                         const Graph& graph, BenchReport* report) {
  SweepPlan plan;
  plan.width = report->width;
  plan.height = report->height;
  plan.frames = std::min(args.frames, 3);
  plan.warmup = 1;
  std::set<std::string> types = args.node_types;
  if (types.empty() && !args.pipeline_only) {
    for (const auto& [id, node] : graph.nodes) types.insert(node.type);
  }
  plan.pipeline = args.node_types.empty();
  progress(args, report->cpu_references ? "sweeping quality settings against CPU references"
                                        : "no CPU references in this build: accuracy sweeps "
                                          "skipped (reconfigure with "
                                          "-DAQUARELLE_BUILD_REFERENCES=ON)");
  auto reference_sweeps = run_reference_sweeps(context, registry, graph, plan, types);
  if (!reference_sweeps.ok()) return refuse(reference_sweeps.message());
  report->sweeps = *reference_sweeps;
  progress(args, "sweeping quality settings at the graph's output and its presets");
  auto graph_sweeps = run_graph_sweeps(context, registry, graph, plan, types);
  if (!graph_sweeps.ok()) return refuse(graph_sweeps.message());
  report->sweeps.insert(report->sweeps.end(), graph_sweeps->begin(), graph_sweeps->end());
  auto layered_sweeps = run_layered_sweeps(context, registry, graph, plan, types);
  if (!layered_sweeps.ok()) return refuse(layered_sweeps.message());
  report->sweeps.insert(report->sweeps.end(), layered_sweeps->begin(), layered_sweeps->end());
  return std::nullopt;
}

// The report as a table or JSON on stdout, and --csv and --plot.
int write_report(const Arguments& args, const BenchReport& report) {
  if (args.json) {
    std::printf("%s\n", report_json(report).dump(2).c_str());
  } else {
    print_report(report, stdout);
  }
  if (!args.csv.empty()) {
    if (auto s = write_report_csv(report, args.csv); !s.ok())
      return refuse("--csv: " + s.message());
  }
  if (!args.plot.empty()) {
    char title[160];
    std::snprintf(title, sizeof(title), "%s %dx%d %s", args.graph_path.c_str(), report.width,
                  report.height, report.precision.c_str());
    if (auto s = write_plot(report.sweeps, title, args.plot); !s.ok())
      return refuse("--plot: " + s.message());
  }
  return kExitOk;
}

int run_bench(Arguments& args) {
  if (auto stop = check_arguments(&args)) return *stop;
  if (!args.plot_from.empty()) return replot(args);
  if (auto device = check_gl_device(args.gl_device); !device.ok())
    return refuse("--gl-device: " + device.message());
  auto backend = parse_backend(args.gl);
  if (!backend.ok()) return refuse("--gl: " + backend.message());
  auto plugins = load_plugins(args.quiet);
  if (!plugins.ok()) return refuse(plugins.message(), kExitEnvironment);
  const Registry& registry = (*plugins)->registry;
  Graph graph;
  if (auto stop = load_graph(args, registry, args.graph_path, true, &graph)) return *stop;
  std::optional<Graph> baseline;
  if (!args.baseline.empty()) {
    baseline.emplace();
    if (auto stop = load_graph(args, registry, args.baseline, false, &*baseline)) return *stop;
  }

  auto context = create_headless_context(*backend, args.gl_device);
  if (!context.ok()) return refuse(context.message(), kExitEnvironment);
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
  if (auto stop =
          time_graph(args, **context, registry, graph, baseline ? &*baseline : nullptr, &report))
    return *stop;
  if (args.sweep) {
    if (auto stop = sweep(args, **context, registry, graph, &report)) return *stop;
  }
  return write_report(args, report);
}

}  // namespace

Command add_bench_command(CLI::App& cli) {
  auto args = std::make_shared<Arguments>();
  CLI::App* command = add_command(
      cli, "bench", "measure speed against error per node and for the pipeline", kBenchHelp,
      "Exit codes: 0 ok, 1 bad input (graph, arguments, files), 2 no usable GL or "
      "plugins.\n");
  declare_options(*command, *args);
  return {command, [args] { return run_bench(*args); }};
}

}  // namespace aq::app
