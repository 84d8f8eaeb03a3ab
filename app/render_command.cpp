// `aquarelle render`: renders a graph's output headless for a frame range, writing each frame
// atomically; EXR keeps linear data, PNG/JPEG/TIFF go through the OCIO display/view transform
// on the GPU.
#include <unistd.h>

#include <aquarelle/core/display_transform.h>
#include <aquarelle/core/evaluator.h>
#include <aquarelle/core/image_io.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <map>

#include "commands.h"
#include "render_guards.h"
#include "render_layers.h"
#include "render_range.h"
#include "session.h"

namespace aq::app {

namespace {

constexpr const char* kRenderHelp =
    R"(usage: aquarelle render GRAPH -o OUT [options]

Renders the graph's output for each frame and writes it to OUT.

  -o, --output OUT        output file; `####` is replaced by the zero-padded frame number
                          (required for frame ranges). .exr keeps scene-linear data;
                          .png/.jpg/.tif get the OCIO display/view transform
  --frames A-B            frames to render (default: the graph's settings.frames)
  --size WxH              override settings.width/height
  --set NODE.PARAM=VALUE  override a parameter (VALUE as JSON, e.g. 0.5, [1,0,0], "text")
  --gl auto|egl|osmesa    GL backend (default auto: EGL, then OSMesa)
  --gl-device D           EGL device: auto (a GPU when EGL lists one, else llvmpipe),
                          software, or an index; a bad one lists the devices
  --precision half|float  working precision (default: settings.precision)
  --quality draft|preview|final   quality preset (default: settings.quality); draft renders
                          at 1/4 of the size, preview at 1/2, final at full size, and the
                          output is resampled to the graph's size
  --view VIEW             OCIO view for display formats (default: the config's default)
  --bits 8|16             bit depth of PNG/TIFF (default 8)
  --float                 write EXR as 32-bit float instead of half
  --stats                 print a table of per-node GPU and CPU time
  --plan                  print the evaluation plan (passes, the nodes each computes, sizes,
                          formats, reads per pixel, what is cached) and render nothing; -o is
                          then not needed
  --resume                skip frames whose output file already exists and reads completely;
                          removes temporaries that killed renders left (.NAME.tmp-PID)
  --layer [NAME=]NODE.PORT  also write that node output as a named layer of a multi-channel
                          EXR (repeatable): in OUT itself when it is .exr, else in
                          OUT.layers.exr; channels normal.X/Y/Z, depth.Z, light.R/G/B/A
  -q, --quiet             no progress output

Exit codes: 0 ok, 1 bad input, 2 no usable GL or plugins, 130 interrupted.
)";

void print_progress(int done, int total, double seconds) {
  const int bar = 30;
  int filled = total > 0 ? done * bar / total : bar;
  std::printf("\r[%.*s%*s] %d/%d frames  %.1f s", filled, "##############################",
              bar - filled, "", done, total, seconds);
  std::fflush(stdout);
}

}  // namespace

int run_render(int argc, char** argv) {
  std::string graph_path, output, frames, size, backend_name = "auto", gl_device = "auto",
                                                precision, quality, view;
  std::vector<std::string> sets;
  std::vector<LayerRequest> layers;
  bool stats = false, resume = false, quiet = false, float_exr = false, print_plan = false;
  int bits = 8;
  for (int i = 1; i < argc; ++i) {
    std::string arg = argv[i];
    auto value = [&]() -> std::string {
      auto v = option_value(argc, argv, &i);
      if (!v.ok()) {
        std::fprintf(stderr, "aquarelle render: %s\n", v.message().c_str());
        std::exit(kExitBadInput);
      }
      return *v;
    };
    if (arg == "--help" || arg == "-h") {
      std::fputs(kRenderHelp, stdout);
      return kExitOk;
    } else if (arg == "-o" || arg == "--output") {
      output = value();
    } else if (arg == "--frames") {
      frames = value();
    } else if (arg == "--size") {
      size = value();
    } else if (arg == "--set") {
      sets.push_back(value());
    } else if (arg == "--gl-device") {
      gl_device = value();
    } else if (arg == "--gl") {
      backend_name = value();
    } else if (arg == "--precision") {
      precision = value();
    } else if (arg == "--quality") {
      quality = value();
    } else if (arg == "--view") {
      view = value();
    } else if (arg == "--bits") {
      std::string b = value();
      if (b != "8" && b != "16") {
        std::fprintf(stderr, "aquarelle render: --bits must be 8 or 16\n");
        return kExitBadInput;
      }
      bits = std::stoi(b);
    } else if (arg == "--float") {
      float_exr = true;
    } else if (arg == "--stats") {
      stats = true;
    } else if (arg == "--plan") {
      print_plan = true;
    } else if (arg == "--layer") {
      auto layer = parse_layer(value());
      if (!layer.ok()) {
        std::fprintf(stderr, "aquarelle render: %s\n", layer.message().c_str());
        return kExitBadInput;
      }
      layers.push_back(*layer);
    } else if (arg == "--resume") {
      resume = true;
    } else if (arg == "-q" || arg == "--quiet") {
      quiet = true;
    } else if (!arg.empty() && arg[0] == '-') {
      std::fprintf(stderr, "aquarelle render: unknown option '%s' (see --help)\n", arg.c_str());
      return kExitBadInput;
    } else if (graph_path.empty()) {
      graph_path = arg;
    } else {
      std::fprintf(stderr, "aquarelle render: more than one graph given ('%s')\n", arg.c_str());
      return kExitBadInput;
    }
  }
  if (graph_path.empty() || (output.empty() && !print_plan)) {
    std::fprintf(stderr, "aquarelle render: %s\n%s",
                 graph_path.empty() ? "no graph file given" : "no output given (-o OUT)",
                 kRenderHelp);
    return kExitBadInput;
  }
  if (auto device = check_gl_device(gl_device); !device.ok()) {
    std::fprintf(stderr, "aquarelle render: --gl-device: %s\n", device.message().c_str());
    return kExitBadInput;
  }
  auto backend = parse_backend(backend_name);
  if (!backend.ok()) {
    std::fprintf(stderr, "aquarelle render: --gl: %s\n", backend.message().c_str());
    return kExitBadInput;
  }
  if (!precision.empty() && precision != "half" && precision != "float") {
    std::fprintf(stderr, "aquarelle render: --precision must be half or float\n");
    return kExitBadInput;
  }
  if (!quality.empty() && quality != "draft" && quality != "preview" && quality != "final") {
    std::fprintf(stderr, "aquarelle render: --quality must be draft, preview or final\n");
    return kExitBadInput;
  }
  install_stop_handlers();
  // Before any plugin loads: a driver that crashes takes down a child, not this process.
  if (auto probe = probe_gl_in_child(*backend, gl_device); !probe.ok()) {
    std::fprintf(stderr, "aquarelle render: --gl %s: %s\n", backend_name.c_str(),
                 probe.message().c_str());
    return kExitEnvironment;
  }

  auto plugins = load_plugins(quiet);
  if (!plugins.ok()) {
    std::fprintf(stderr, "aquarelle render: %s\n", plugins.message().c_str());
    return kExitEnvironment;
  }
  const Registry& registry = (*plugins)->registry;
  ReadResult read = read_graph_file(graph_path, registry);
  if (!read.ok()) {
    std::fprintf(stderr, "%s\n", format_problems(read.problems).c_str());
    return kExitBadInput;
  }
  Graph graph = std::move(read.graph);
  Settings& settings = graph.settings;
  if (!size.empty()) {
    if (auto s = parse_size(size, &settings.width, &settings.height); !s.ok()) {
      std::fprintf(stderr, "aquarelle render: %s\n", s.message().c_str());
      return kExitBadInput;
    }
  }
  // The range to render; settings.first_frame stays the graph's, since time is measured
  // from it: a farm rendering 25-48 must see the same time at frame 25 as a 1-48 run.
  int first = settings.first_frame, last = settings.last_frame;
  if (!frames.empty()) {
    if (auto s = parse_frames(frames, &first, &last); !s.ok()) {
      std::fprintf(stderr, "aquarelle render: %s\n", s.message().c_str());
      return kExitBadInput;
    }
  }
  if (!precision.empty()) settings.precision = precision;
  if (!quality.empty()) settings.quality = quality;
  for (const auto& assignment : sets) {
    if (auto s = apply_setting(graph, registry, assignment); !s.ok()) {
      std::fprintf(stderr, "aquarelle render: %s\n", s.message().c_str());
      return kExitBadInput;
    }
  }
  if (auto problems = validate_graph(graph, registry); !problems.empty()) {
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
    std::fprintf(stderr, "%s\n", format_problems(problems).c_str());
    return kExitBadInput;
  }
  if (auto s = check_layers(layers, graph, registry); !s.ok()) {
    std::fprintf(stderr, "aquarelle render: %s\n", s.message().c_str());
    return kExitBadInput;
  }
  if (print_plan) {
    auto plan = compile_plan(graph, registry, PlanOptions{});
    if (!plan.ok()) {
      std::fprintf(stderr, "aquarelle render: %s\n", plan.message().c_str());
      return kExitBadInput;
    }
    std::fputs(format_plan(*plan).c_str(), stdout);
    return kExitOk;
  }
  if (frames.empty() && output.find('#') == std::string::npos && last > first) {
    // One output file and no explicit range: a still of the first frame, like a viewer.
    if (!quiet) {
      std::fprintf(stderr,
                   "aquarelle: rendering frame %d only; use --frames %d-%d and `####` in the "
                   "output name for the whole range\n",
                   first, first, last);
    }
    last = first;
  }
  if (last > first && output.find('#') == std::string::npos) {
    std::fprintf(stderr,
                 "aquarelle render: rendering frames %d-%d needs `####` in the output name "
                 "for the frame number, e.g. -o out/####.png\n",
                 first, last);
    return kExitBadInput;
  }
  std::error_code ec;
  std::filesystem::path out_dir = std::filesystem::path(frame_path(output, first)).parent_path();
  if (!out_dir.empty() && !std::filesystem::is_directory(out_dir, ec)) {
    std::fprintf(stderr, "aquarelle render: output folder '%s' does not exist: create it first\n",
                 out_dir.string().c_str());
    return kExitBadInput;
  }
  const std::vector<ReadFile> inputs = graph_input_files(graph, registry);
  auto side_file = [&](const std::string& path) { return layers.empty() ? "" : layers_path(path); };
  if (auto s = check_frame_outputs(frame_path(output, first), side_file(frame_path(output, first)),
                                   inputs);
      !s.ok()) {
    std::fprintf(stderr, "aquarelle render: %s\n", s.message().c_str());
    return kExitBadInput;
  }
  bool display = is_display_referred_format(frame_path(output, first));

  auto color = ColorConfig::load();
  if (!color.ok()) {
    std::fprintf(stderr, "aquarelle render: %s\n", color.message().c_str());
    return kExitEnvironment;
  }
  std::optional<DisplayTransform> transform;
  if (display) {
    auto t = DisplayTransform::create(*color, "", view);
    if (!t.ok()) {
      // An unknown --view is the user's; anything else is the config's (a broken LUT...).
      if (!view.empty() && t.message().find("unknown view") != std::string::npos) {
        std::fprintf(stderr, "aquarelle render: --view: %s\n", t.message().c_str());
        return kExitBadInput;
      }
      std::fprintf(stderr,
                   "aquarelle render: the OpenColorIO config %s%s is unusable: %s (fix it%s)\n",
                   color->path().c_str(), std::getenv("OCIO") != nullptr ? " (from $OCIO)" : "",
                   t.message().c_str(),
                   std::getenv("OCIO") != nullptr ? ", or unset $OCIO to use Aquarelle's own" : "");
      return kExitEnvironment;
    }
    transform = std::move(*t);
  }

  auto context = create_headless_context(*backend, gl_device);
  if (!context.ok()) {
    std::fprintf(stderr, "aquarelle render: %s\n", context.message().c_str());
    return kExitEnvironment;
  }
  if (!quiet) std::fprintf(stderr, "aquarelle: %s\n", (*context)->description().c_str());

  const bool progress = !quiet && isatty(STDOUT_FILENO) && last > first;
  Evaluator evaluator(**context, registry);
  std::map<std::string, std::pair<NodeTiming, int>> totals;
  std::vector<std::string> order;
  auto start = std::chrono::steady_clock::now();
  RangeRequest request;
  request.output = output;
  request.first = first;
  request.last = last;
  request.resume = resume;
  request.eval.measure_gpu_time = stats;
  request.eval.finish_each_node = stats;  // timestamps without a flush under-read on llvmpipe
  request.eval.retain_outputs = false;    // textures return to the pool after their last reader
  if (!layers.empty()) request.eval.retain_outputs = true;  // layers reuse the frame's results
  request.write.bits = bits;
  request.write.float_data = float_exr;
  request.transform = transform ? &*transform : nullptr;
  RangeHooks hooks;
  hooks.stop_requested = stop_requested;
  hooks.check_path = [&](const std::string& path) {
    return check_frame_outputs(path, side_file(path), inputs);
  };
  hooks.write_frame = [&](const std::string& path, const EvalOptions& options,
                          const ImageF& pixels) -> Status {
    if (layers.empty()) return write_image(path, pixels, request.write);
    // Layers in a file of their own go first, so --resume, which looks at the main image, never
    // skips a frame whose layers are missing.
    if (layers_path(path) == path) {
      return write_layers(evaluator, graph, options, layers, &pixels, path, request.write);
    }
    if (auto s = write_layers(evaluator, graph, options, layers, nullptr, layers_path(path),
                              request.write);
        !s.ok()) {
      return s;
    }
    return write_image(path, pixels, request.write);
  };
  hooks.frame_done = [&](const FrameReport& report) {
    if (report.skipped) return;
    for (const auto& timing : evaluator.last_timings()) {
      auto [it, inserted] = totals.try_emplace(timing.node, timing, 0);
      if (inserted) {
        order.push_back(timing.node);
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
    double seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    if (progress) print_progress(report.done, report.total, seconds);
  };
  const RangeOutcome outcome = render_range(evaluator, graph, request, hooks);
  if (outcome.failure) {
    if (progress) std::printf("\n");
    std::fprintf(stderr, "aquarelle render: %s\n", outcome.failure->message.c_str());
    return outcome.failure->environment ? kExitEnvironment : kExitBadInput;
  }
  const int written = outcome.written, skipped = outcome.skipped;
  const int exit_code = outcome.interrupted ? kExitInterrupted : kExitOk;
  cancel_forced_stop();
  if (transform) transform->release_gl();
  if (progress) std::printf("\n");
  if (!quiet) {
    std::fprintf(stderr, "aquarelle: wrote %d frame(s)%s to %s\n", written,
                 skipped > 0 ? (" (" + std::to_string(skipped) + " already there)").c_str() : "",
                 output.c_str());
  }
  if (stats) {
    int frames_run = std::max(1, written);
    // redrawn: the share of its outputs' pixels a run redrew on average (damage tracking: a node
    // whose outputs were kept redraws only what changed).
    std::printf("%-16s %-12s %10s %10s %6s %8s\n", "node", "type", "gpu ms", "cpu ms", "runs",
                "redrawn");
    double gpu_total = 0, cpu_total = 0;
    for (const auto& id : order) {
      const auto& [timing, runs] = totals[id];
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
  if (exit_code == kExitInterrupted) {
    std::fprintf(stderr,
                 "aquarelle render: interrupted; %d complete frame(s) written, "
                 "run again with --resume to finish\n",
                 written);
  }
  return exit_code;
}

}  // namespace aq::app
