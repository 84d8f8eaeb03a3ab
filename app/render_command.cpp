// `aquarelle render`: renders a graph's output headless for a frame range, writing each frame
// atomically; EXR keeps linear data, PNG/JPEG/TIFF go through the OCIO display/view transform
// on the GPU. The steps, in order: check the arguments, probe GL, load the plugins and the
// graph (overrides applied, validated), check where the frames go, then render the range
// (render_range.h) and report.
#include <unistd.h>

#include <aquarelle/core/display_transform.h>
#include <aquarelle/core/evaluator.h>
#include <aquarelle/core/image_io.h>
#include <aquarelle/core/message_text.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "commands.h"
#include "render_guards.h"
#include "render_layers.h"
#include "render_range.h"
#include "session.h"

namespace aq::app {

namespace {

constexpr const char* kRenderHelp =
    R"(usage: aquarelle render GRAPH -o OUT [options]

Renders the graph's output for each frame and writes it to OUT.)";

struct RenderArguments {
  std::vector<std::string> graphs;
  std::string output, frames, size, backend_name = "auto", gl_device = "auto", precision, quality,
                                    view, bits = "8";
  std::vector<std::string> sets, layers;
  bool stats = false, resume = false, quiet = false, float_exr = false, print_plan = false;
};

void declare_options(CLI::App& command, RenderArguments& args) {
  command.add_option("GRAPH", args.graphs, "the graph file");
  command
      .add_option("-o,--output", args.output,
                  "output file; `####` is replaced by the zero-padded frame number\n"
                  "(required for frame ranges). .exr keeps scene-linear data;\n"
                  ".png/.jpg/.tif get the OCIO display/view transform")
      ->type_name("OUT");
  command
      .add_option("--frames", args.frames,
                  "frames to render (default: the graph's settings.frames)")
      ->type_name("A-B");
  command.add_option("--size", args.size, "override settings.width/height")->type_name("WxH");
  command
      .add_option("--set", args.sets,
                  "override a parameter (VALUE as JSON, e.g. 0.5, [1,0,0], \"text\")")
      ->type_name("NODE.PARAM=VALUE")
      ->allow_extra_args(false);
  command.add_option("--gl", args.backend_name, "GL backend (default auto: EGL, then OSMesa)")
      ->type_name("auto|egl|osmesa");
  command
      .add_option("--gl-device", args.gl_device,
                  "EGL device: auto (a GPU when EGL lists one, else llvmpipe),\n"
                  "software, or an index; a bad one lists the devices")
      ->type_name("D");
  command
      .add_option("--precision", args.precision, "working precision (default: settings.precision)")
      ->type_name("half|float");
  command
      .add_option("--quality", args.quality,
                  "quality preset (default: settings.quality); draft renders\n"
                  "at 1/4 of the size, preview at 1/2, final at full size, and the\n"
                  "output is resampled to the graph's size")
      ->type_name("draft|preview|final");
  command
      .add_option("--view", args.view,
                  "OCIO view for display formats (default: the config's default)")
      ->type_name("VIEW");
  command.add_option("--bits", args.bits, "bit depth of PNG/TIFF (default 8)")->type_name("8|16");
  command.add_flag("--float", args.float_exr, "write EXR as 32-bit float instead of half");
  command.add_flag("--stats", args.stats, "print a table of per-node GPU and CPU time");
  command.add_flag("--plan", args.print_plan,
                   "print the evaluation plan (passes, the nodes each computes, sizes,\n"
                   "formats, reads per pixel, what is cached) and render nothing; -o is\n"
                   "then not needed");
  command.add_flag("--resume", args.resume,
                   "skip frames whose output file already exists and reads completely;\n"
                   "removes temporaries that killed renders left (.NAME.tmp-PID)");
  command
      .add_option("--layer", args.layers,
                  "also write that node output as a named layer of a multi-channel\n"
                  "EXR (repeatable): in OUT itself when it is .exr, else in\n"
                  "OUT.layers.exr; channels normal.X/Y/Z, depth.Z, light.R/G/B/A")
      ->type_name("[NAME=]NODE.PORT")
      ->allow_extra_args(false);
  command.add_flag("-q,--quiet", args.quiet, "no progress output");
}

// Messages may quote arguments: escaped, so a newline or ESC in one cannot forge a line.
int refuse(const std::string& message, int code = kExitBadInput) {
  std::fprintf(stderr, "aquarelle render: %s\n", escape_for_message(message).c_str());
  return code;
}

// The checks that need nothing but the arguments; `layers` gets the parsed --layer values.
std::optional<int> check_arguments(const RenderArguments& args, const CLI::App& command,
                                   std::vector<LayerRequest>* layers) {
  if (args.bits != "8" && args.bits != "16") return refuse("--bits must be 8 or 16");
  for (const auto& text : args.layers) {
    auto layer = parse_layer(text);
    if (!layer.ok()) return refuse(layer.message());
    layers->push_back(*layer);
  }
  if (args.graphs.size() > 1) return refuse("more than one graph given ('" + args.graphs[1] + "')");
  if (args.graphs.empty() || (args.output.empty() && !args.print_plan)) {
    std::fprintf(stderr, "aquarelle render: %s\n%s",
                 args.graphs.empty() ? "no graph file given" : "no output given (-o OUT)",
                 command.help().c_str());
    return kExitBadInput;
  }
  if (auto device = check_gl_device(args.gl_device); !device.ok())
    return refuse("--gl-device: " + device.message());
  if (auto backend = parse_backend(args.backend_name); !backend.ok())
    return refuse("--gl: " + backend.message());
  if (!args.precision.empty() && args.precision != "half" && args.precision != "float")
    return refuse("--precision must be half or float");
  if (!args.quality.empty() && args.quality != "draft" && args.quality != "preview" &&
      args.quality != "final")
    return refuse("--quality must be draft, preview or final");
  return std::nullopt;
}

// Problems of the graph after the overrides, each placed: in the graph file, or at the --set
// that gave the value.
std::string placed_problems(std::vector<Problem> problems, const std::string& graph_path,
                            const std::vector<std::string>& sets) {
  for (auto& p : problems) {
    p.file = graph_path;
    // A value given with --set is the command line's, not the graph file's.
    for (const auto& assignment : sets) {
      if (!p.node.empty() && !p.field.empty() &&
          assignment.rfind(p.node + "." + p.field + "=", 0) == 0) {
        p.file = "--set " + assignment;
        p.line = p.column = 0;
      }
    }
  }
  return format_problems(problems);
}

// Reads the graph, applies --size, --frames, --precision, --quality and --set, and validates it.
// `first`..`last` is the range to render; settings.first_frame stays the graph's, since time is
// measured from it: a farm rendering 25-48 must see the same time at frame 25 as a 1-48 run.
std::optional<int> load_graph(const RenderArguments& args, const Registry& registry, Graph* graph,
                              int* first, int* last) {
  ReadResult read = read_graph_file(args.graphs[0], registry);
  if (!read.ok()) {
    std::fprintf(stderr, "%s\n", format_problems(read.problems).c_str());
    return kExitBadInput;
  }
  *graph = std::move(read.graph);
  Settings& settings = graph->settings;
  if (!args.size.empty()) {
    if (auto s = parse_size(args.size, &settings.width, &settings.height); !s.ok())
      return refuse(s.message());
  }
  *first = settings.first_frame;
  *last = settings.last_frame;
  if (!args.frames.empty()) {
    if (auto s = parse_frames(args.frames, first, last); !s.ok()) return refuse(s.message());
  }
  if (!args.precision.empty()) settings.precision = args.precision;
  if (!args.quality.empty()) settings.quality = args.quality;
  for (const auto& assignment : args.sets) {
    if (auto s = apply_setting(*graph, registry, assignment); !s.ok()) return refuse(s.message());
  }
  if (auto problems = validate_graph(*graph, registry); !problems.empty()) {
    std::fprintf(stderr, "%s\n", placed_problems(problems, args.graphs[0], args.sets).c_str());
    return kExitBadInput;
  }
  return std::nullopt;
}

// Where the frames go: one file without `####` renders a still; the folder must exist and no
// frame may overwrite one of the graph's inputs.
std::optional<int> check_output(const RenderArguments& args, int first, int* last,
                                const std::vector<ReadFile>& inputs) {
  const std::string& output = args.output;
  if (args.frames.empty() && output.find('#') == std::string::npos && *last > first) {
    // One output file and no explicit range: a still of the first frame, like a viewer.
    if (!args.quiet) {
      std::fprintf(stderr,
                   "aquarelle: rendering frame %d only; use --frames %d-%d and `####` in the "
                   "output name for the whole range\n",
                   first, first, *last);
    }
    *last = first;
  }
  if (*last > first && output.find('#') == std::string::npos) {
    return refuse("rendering frames " + std::to_string(first) + "-" + std::to_string(*last) +
                  " needs `####` in the output name for the frame number, e.g. -o out/####.png");
  }
  std::error_code ec;
  std::filesystem::path out_dir = std::filesystem::path(frame_path(output, first)).parent_path();
  if (!out_dir.empty() && !std::filesystem::is_directory(out_dir, ec)) {
    return refuse("output folder '" + out_dir.string() + "' does not exist: create it first");
  }
  const std::string first_file = frame_path(output, first);
  if (auto s = check_frame_outputs(first_file, args.layers.empty() ? "" : layers_path(first_file),
                                   inputs);
      !s.ok())
    return refuse(s.message());
  return std::nullopt;
}

// The OCIO display/view transform for display-referred outputs (none for EXR).
std::optional<int> make_transform(const RenderArguments& args, int first,
                                  std::optional<DisplayTransform>* transform) {
  auto color = ColorConfig::load();
  if (!color.ok()) return refuse(color.message(), kExitEnvironment);
  if (!is_display_referred_format(frame_path(args.output, first))) return std::nullopt;
  auto t = DisplayTransform::create(*color, "", args.view);
  if (t.ok()) {
    *transform = std::move(*t);
    return std::nullopt;
  }
  // An unknown --view is the user's; anything else is the config's (a broken LUT...).
  if (!args.view.empty() && t.message().find("unknown view") != std::string::npos)
    return refuse("--view: " + t.message());
  const bool from_env = std::getenv("OCIO") != nullptr;
  return refuse("the OpenColorIO config " + color->path() + (from_env ? " (from $OCIO)" : "") +
                    " is unusable: " + t.message() + " (fix it" +
                    (from_env ? ", or unset $OCIO to use Aquarelle's own" : "") + ")",
                kExitEnvironment);
}

// --stats: per node, its times summed over the frames, its runs and the share it redrew.
class StatsTable {
 public:
  void add(const std::vector<NodeTiming>& timings) {
    for (const auto& timing : timings) {
      auto [it, inserted] = totals_.try_emplace(timing.node, timing, 0);
      if (inserted) {
        order_.push_back(timing.node);
        it->second.first.gpu_ms = it->second.first.cpu_ms = 0;
        it->second.first.redrawn = 0;
      }
      it->second.first.gpu_ms += timing.gpu_ms;
      it->second.first.cpu_ms += timing.cpu_ms;
      if (!timing.cached && !timing.fused) {
        ++it->second.second;
        it->second.first.redrawn += timing.redrawn;
      }
      if (timing.fused) it->second.first.fused = true;
    }
  }

  // redrawn: the share of its outputs' pixels a run redrew on average (damage tracking: a node
  // whose outputs were kept redraws only what changed).
  void print(int written) {
    const int frames_run = std::max(1, written);
    std::printf("%-16s %-12s %10s %10s %6s %8s\n", "node", "type", "gpu ms", "cpu ms", "runs",
                "redrawn");
    double gpu_total = 0, cpu_total = 0;
    for (const auto& id : order_) {
      const auto& [timing, runs] = totals_[id];
      if (timing.fused) {
        std::printf("%-16s %-12s %28s\n", id.c_str(), timing.type.c_str(), "fused into its reader");
        continue;
      }
      char redrawn[16] = "-";
      if (runs > 0 && timing.redrawn >= 0)
        std::snprintf(redrawn, sizeof(redrawn), "%.0f%%", 100.0 * timing.redrawn / runs);
      std::printf("%-16s %-12s %10.2f %10.2f %6d %8s\n", id.c_str(), timing.type.c_str(),
                  timing.gpu_ms / frames_run, timing.cpu_ms / frames_run, runs, redrawn);
      gpu_total += timing.gpu_ms / frames_run;
      cpu_total += timing.cpu_ms / frames_run;
    }
    std::printf("%-16s %-12s %10.2f %10.2f\n", "total/frame", "", gpu_total, cpu_total);
  }

 private:
  std::map<std::string, std::pair<NodeTiming, int>> totals_;
  std::vector<std::string> order_;
};

void print_progress(int done, int total, double seconds) {
  const int bar = 30;
  int filled = total > 0 ? done * bar / total : bar;
  std::printf("\r[%.*s%*s] %d/%d frames  %.1f s", filled, "##############################",
              bar - filled, "", done, total, seconds);
  std::fflush(stdout);
}

// What render_frames needs besides the arguments.
struct RenderJob {
  const Graph* graph = nullptr;
  const Registry* registry = nullptr;
  GlBackend backend{};
  int first = 1, last = 1;
  std::vector<LayerRequest> layers;
  std::vector<ReadFile> inputs;           // every file the render reads, never overwritten
  DisplayTransform* transform = nullptr;  // display-referred outputs only
};

// Writes a frame's image and its --layer outputs. Layers in a file of their own go first, so
// --resume, which looks at the main image, never skips a frame whose layers are missing.
Status write_frame(Evaluator& evaluator, const RenderJob& job, const std::string& path,
                   const EvalOptions& options, const ImageF& pixels, const WriteOptions& write) {
  if (job.layers.empty()) return write_image(path, pixels, write);
  if (layers_path(path) == path)
    return write_layers(evaluator, *job.graph, options, job.layers, &pixels, path, write);
  if (auto s = write_layers(evaluator, *job.graph, options, job.layers, nullptr, layers_path(path),
                            write);
      !s.ok())
    return s;
  return write_image(path, pixels, write);
}

RangeRequest range_request(const RenderArguments& args, const RenderJob& job) {
  RangeRequest request;
  request.output = args.output;
  request.first = job.first;
  request.last = job.last;
  request.resume = args.resume;
  request.eval.measure_gpu_time = args.stats;
  request.eval.finish_each_node = args.stats;  // timestamps without a flush under-read on llvmpipe
  request.eval.retain_outputs = false;  // textures return to the pool after their last reader
  if (!job.layers.empty()) request.eval.retain_outputs = true;  // layers reuse the frame's results
  request.write.bits = std::stoi(args.bits);
  request.write.float_data = args.float_exr;
  request.transform = job.transform;
  return request;
}

// Renders the range and reports what was written (and --stats).
int render_frames(const RenderArguments& args, const RenderJob& job) {
  auto context = create_headless_context(job.backend, args.gl_device);
  if (!context.ok()) return refuse(context.message(), kExitEnvironment);
  if (!args.quiet) std::fprintf(stderr, "aquarelle: %s\n", (*context)->description().c_str());

  const bool progress = !args.quiet && isatty(STDOUT_FILENO) && job.last > job.first;
  Evaluator evaluator(**context, *job.registry);
  StatsTable stats;
  const auto start = std::chrono::steady_clock::now();
  const RangeRequest request = range_request(args, job);
  RangeHooks hooks;
  hooks.stop_requested = stop_requested;
  hooks.check_path = [&](const std::string& path) {
    return check_frame_outputs(path, job.layers.empty() ? "" : layers_path(path), job.inputs);
  };
  hooks.write_frame = [&](const std::string& path, const EvalOptions& options,
                          const ImageF& pixels) {
    return write_frame(evaluator, job, path, options, pixels, request.write);
  };
  hooks.frame_done = [&](const FrameReport& report) {
    if (report.skipped) return;
    stats.add(evaluator.last_timings());
    const auto elapsed = std::chrono::steady_clock::now() - start;
    if (progress)
      print_progress(report.done, report.total, std::chrono::duration<double>(elapsed).count());
  };
  const RangeOutcome outcome = render_range(evaluator, *job.graph, request, hooks);
  if (outcome.failure) {
    if (progress) std::printf("\n");
    return refuse(outcome.failure->message,
                  outcome.failure->environment ? kExitEnvironment : kExitBadInput);
  }
  cancel_forced_stop();
  if (job.transform != nullptr) job.transform->release_gl();
  if (progress) std::printf("\n");
  if (!args.quiet) {
    const std::string there =
        outcome.skipped > 0 ? " (" + std::to_string(outcome.skipped) + " already there)" : "";
    std::fprintf(stderr, "aquarelle: wrote %d frame(s)%s to %s\n", outcome.written, there.c_str(),
                 args.output.c_str());
  }
  if (args.stats) stats.print(outcome.written);
  if (!outcome.interrupted) return kExitOk;
  std::fprintf(stderr,
               "aquarelle render: interrupted; %d complete frame(s) written, "
               "run again with --resume to finish\n",
               outcome.written);
  return kExitInterrupted;
}

int run_render(const RenderArguments& args, const CLI::App& command) {
  RenderJob job;
  if (auto stop = check_arguments(args, command, &job.layers)) return *stop;
  job.backend = *parse_backend(args.backend_name);
  install_stop_handlers();
  // Before any plugin loads: a driver that crashes takes down a child, not this process.
  if (auto probe = probe_gl_in_child(job.backend, args.gl_device); !probe.ok())
    return refuse("--gl " + args.backend_name + ": " + probe.message(), kExitEnvironment);
  auto plugins = load_plugins(args.quiet);
  if (!plugins.ok()) return refuse(plugins.message(), kExitEnvironment);
  const Registry& registry = (*plugins)->registry;
  Graph graph;
  if (auto stop = load_graph(args, registry, &graph, &job.first, &job.last)) return *stop;
  if (auto s = check_layers(job.layers, graph, registry); !s.ok()) return refuse(s.message());
  if (args.print_plan) {
    auto plan = compile_plan(graph, registry, PlanOptions{});
    if (!plan.ok()) return refuse(plan.message());
    std::fputs(format_plan(*plan).c_str(), stdout);
    return kExitOk;
  }
  job.inputs = graph_input_files(graph, registry);
  if (auto stop = check_output(args, job.first, &job.last, job.inputs)) return *stop;
  std::optional<DisplayTransform> transform;
  if (auto stop = make_transform(args, job.first, &transform)) return *stop;
  job.graph = &graph;
  job.registry = &registry;
  job.transform = transform ? &*transform : nullptr;
  return render_frames(args, job);
}

}  // namespace

Command add_render_command(CLI::App& cli) {
  auto args = std::make_shared<RenderArguments>();
  CLI::App* command =
      add_command(cli, "render", "render a graph headless to image files", kRenderHelp,
                  "Exit codes: 0 ok, 1 bad input, 2 no usable GL or plugins, 130 "
                  "interrupted.\n");
  declare_options(*command, *args);
  return {command, [args, command] { return run_render(*args, *command); }};
}

}  // namespace aq::app
