// Text, JSON and CSV renderings of a `aquarelle bench` report (see bench_report.h).
#include "bench_report.h"

#include <aquarelle/core/write_guard.h>
#include <aquarelle/sdk/regular_file.hpp>

#include <unistd.h>
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>

#include "bench_plot.h"

namespace aq::app {

namespace {

using json = nlohmann::json;

// JSON has no infinity or NaN: those become null.
json number(double value) {
  return std::isfinite(value) ? json(value) : json(nullptr);
}

json spread_json(const Spread& s) {
  return {{"median", number(s.median)}, {"min", number(s.min)}, {"q1", number(s.q1)},
          {"q3", number(s.q3)},         {"max", number(s.max)}, {"count", s.count}};
}

double ratio(double frame_ms, double copy_ms) {
  return copy_ms > 0 ? frame_ms / copy_ms : 0.0;
}

// A node's error against its exact setting (bench_node_error.h); null when it has none.
json node_error_json(const std::map<std::string, NodeError>& errors, const std::string& id) {
  const auto found = errors.find(id);
  if (found == errors.end()) return nullptr;
  const NodeError& e = found->second;
  return {{"against", e.against},
          {"exact", e.exact},
          {"max_abs", number(e.error.max_abs)},
          {"mean_abs", number(e.error.mean_abs)},
          {"psnr", number(e.error.psnr)},
          {"note", e.note}};
}

json pipeline_json(const PipelineTiming& timing, double copy_ms,
                   const std::map<std::string, NodeError>& errors) {
  json nodes = json::array();
  for (const auto& n : timing.nodes) {
    nodes.push_back({{"id", n.id},
                     {"type", n.type},
                     {"wall_ms", spread_json(n.wall_ms)},
                     {"gpu_ms", spread_json(n.gpu_ms)},
                     {"copy_passes", ratio(n.wall_ms.median, copy_ms)},
                     {"runs", n.runs},
                     {"fused", n.fused},
                     {"error", node_error_json(errors, n.id)}});
  }
  return {{"static_nodes_cached", timing.static_cached},
          {"frame_ms", spread_json(timing.frame_ms)},
          {"node_wall_sum_ms", spread_json(timing.node_wall_sum_ms)},
          {"copy_passes_per_frame", ratio(timing.frame_ms.median, copy_ms)},
          {"nodes", nodes}};
}

// The table's error column: mean and max abs against the exact node, "exact" when the node
// runs at its exact setting, blank for nodes without an approximation.
std::string error_cell(const std::map<std::string, NodeError>& errors, const std::string& id) {
  const auto found = errors.find(id);
  if (found == errors.end()) return "";
  if (found->second.exact) return "     exact";
  char cell[48];
  std::snprintf(cell, sizeof(cell), "%10.3g %10.3g", found->second.error.mean_abs,
                found->second.error.max_abs);
  return cell;
}

void print_error_legend(const std::map<std::string, NodeError>& errors, std::FILE* out) {
  if (errors.empty()) return;
  std::fprintf(out,
               "error: the node's output against the same node at its exact setting, same inputs, "
               "first frame:");
  for (const auto& [id, e] : errors) {
    std::fprintf(out, " %s (%s%s%s);", id.c_str(), e.against.c_str(), e.note.empty() ? "" : ": ",
                 e.note.c_str());
  }
  std::fprintf(out, "\n");
}

std::string csv_field(const std::string& text) {
  if (text.find_first_of(",\"\n") == std::string::npos) return text;
  std::string quoted = "\"";
  for (char c : text) quoted += c == '"' ? std::string("\"\"") : std::string(1, c);
  return quoted + "\"";
}

std::string csv_number(double value) {
  if (std::isnan(value)) return "nan";
  if (std::isinf(value)) return value > 0 ? "inf" : "-inf";
  char buffer[32];
  std::snprintf(buffer, sizeof(buffer), "%.6g", value);
  return buffer;
}

// --baseline's figures, null without it.
json baseline_json(const BenchReport& r) {
  if (!r.baseline) return nullptr;
  return {{"graph", r.baseline_graph},
          {"frame_ms", spread_json(r.baseline->graph_ms)},
          {"baseline_frame_ms", spread_json(r.baseline->baseline_ms)},
          {"ratio_of_medians",
           number(ratio(r.baseline->graph_ms.median, r.baseline->baseline_ms.median))},
          {"pair_ratio", spread_json(r.baseline->pair_ratio)}};
}

}  // namespace

double BenchReport::copy_passes_per_frame() const {
  return ratio(cached.frame_ms.median, copy_pass.wall_ms.median);
}
double BenchReport::copy_passes_per_frame_every_node_runs() const {
  return ratio(every_node_runs.frame_ms.median, copy_pass.wall_ms.median);
}

json report_json(const BenchReport& r) {
  json sweeps = json::array();
  for (const auto& sweep : r.sweeps) {
    json points = json::array();
    const auto front = pareto_points(sweep);
    for (size_t i = 0; i < sweep.points.size(); ++i) {
      const auto& p = sweep.points[i];
      points.push_back({{"setting", p.setting},
                        {"params", p.params},
                        {"precision", p.precision},
                        {"time_ms", spread_json(p.time_ms)},
                        {"gpu_ms", spread_json(p.gpu_ms)},
                        {"max_abs", number(p.error.max_abs)},
                        {"mean_abs", number(p.error.mean_abs)},
                        {"psnr", number(p.error.psnr)},
                        {"is_reference", p.is_reference},
                        {"pareto", std::find(front.begin(), front.end(), i) != front.end()}});
    }
    sweeps.push_back({{"series", sweep.series},
                      {"node", sweep.node_type},
                      {"kind", sweep.kind},
                      {"reference", sweep.reference},
                      {"reference_ms", number(sweep.reference_ms)},
                      {"time_measure", sweep.time_measure},
                      {"note", sweep.note},
                      {"points", points}});
  }
  const double copy_ms = r.copy_pass.wall_ms.median;
  return {
      {"graph", r.graph},
      {"gl", r.gl},
      {"size", {r.width, r.height}},
      {"precision", r.precision},
      {"quality", r.quality},
      {"frames", r.frames},
      {"warmup", r.warmup},
      {"copy_pass_ms", number(copy_ms)},
      {"copy_pass",
       {{"wall_ms", spread_json(r.copy_pass.wall_ms)},
        {"timestamp_ms", spread_json(r.copy_pass.timestamp_ms)}}},
      {"frame_ms", number(r.cached.frame_ms.median)},
      {"copy_passes_per_frame", number(r.copy_passes_per_frame())},
      {"copy_passes_per_frame_every_node_runs", number(r.copy_passes_per_frame_every_node_runs())},
      {"nodes", pipeline_json(r.every_node_runs, copy_ms, r.node_errors)["nodes"]},
      {"modes",
       {{"every_node_runs", pipeline_json(r.every_node_runs, copy_ms, r.node_errors)},
        {"cached_static_nodes", pipeline_json(r.cached, copy_ms, r.node_errors)}}},
      {"cpu_references", r.cpu_references},
      {"references_note", r.cpu_references
                              ? "CPU references linked (reference/, aquarelle_reference)"
                              : "no CPU references in this build: node accuracy sweeps skipped "
                                "(reconfigure with -DAQUARELLE_BUILD_REFERENCES=ON)"},
      {"sweeps", sweeps},
      {"baseline", baseline_json(r)}};
}

void print_report(const BenchReport& r, std::FILE* out) {
  const double copy_ms = r.copy_pass.wall_ms.median;
  std::fprintf(out,
               "graph %s at %dx%d, quality %s, %s precision, %d timed frames after %d warm-up\n",
               r.graph.c_str(), r.width, r.height, r.quality.c_str(), r.precision.c_str(), r.frames,
               r.warmup);
  std::fprintf(out, "%s\n\n", r.gl.c_str());
  std::fprintf(out,
               "copy pass (%s): %.3f ms median [%.3f .. %.3f] (wall, glFinish-bounded batches; "
               "GL timestamps say %.3f)\n\n",
               r.precision == "float" ? "RGBA32F" : "RGBA16F", copy_ms, r.copy_pass.wall_ms.min,
               r.copy_pass.wall_ms.max, r.copy_pass.timestamp_ms.median);
  std::fprintf(out,
               "node time: process() between two glFinish calls (wall); copies = median / "
               "copy pass\n");
  std::fprintf(out, "%-14s %-12s %36s %27s %10s %21s\n", "node", "type", "every node runs: ms",
               "static cached: ms", "GL tstamp", "error vs exact node");
  std::fprintf(out, "%-14s %-12s %9s %17s %8s %9s %17s %10s %10s %10s\n", "", "", "median",
               "[min .. max]", "copies", "median", "[min .. max]", "ms", "mean abs", "max abs");
  for (size_t i = 0; i < r.every_node_runs.nodes.size(); ++i) {
    const NodeStats& n = r.every_node_runs.nodes[i];
    const NodeStats* c = nullptr;
    for (const auto& candidate : r.cached.nodes) {
      if (candidate.id == n.id) c = &candidate;
    }
    char cached[64] = "-";
    if (n.fused) {  // its time is in its reader's row; its error is its own
      std::fprintf(out, "%-14s %-12s %36s %27s %10s %s\n", n.id.c_str(), n.type.c_str(),
                   "fused into its reader's pass", "", "", error_cell(r.node_errors, n.id).c_str());
      continue;
    }
    if (c != nullptr) {
      std::snprintf(cached, sizeof(cached), "%9.3f [%6.3f .. %6.3f]", c->wall_ms.median,
                    c->wall_ms.min, c->wall_ms.max);
    }
    std::fprintf(out, "%-14s %-12s %9.3f [%6.3f .. %6.3f] %8.1f %27s %10.3f %s\n", n.id.c_str(),
                 n.type.c_str(), n.wall_ms.median, n.wall_ms.min, n.wall_ms.max,
                 ratio(n.wall_ms.median, copy_ms), cached, n.gpu_ms.median,
                 error_cell(r.node_errors, n.id).c_str());
  }
  print_error_legend(r.node_errors, out);
  std::fprintf(out,
               "\nframe (wall, timers off): every node runs %.3f ms = %.1f copy passes; "
               "static nodes cached %.3f ms = %.1f copy passes\n",
               r.every_node_runs.frame_ms.median, r.copy_passes_per_frame_every_node_runs(),
               r.cached.frame_ms.median, r.copy_passes_per_frame());
  // The frame runs without per-node waits, the node table with them, in separate loops: the sum
  // beside the frame tells the two apart (their gap is not evaluator work; docs/performance.md).
  std::fprintf(
      out,
      "nodes' own times summed per frame (glFinish around each), median: every node runs %.3f ms "
      "= %.1f copy passes; static nodes cached %.3f ms = %.1f copy passes\n",
      r.every_node_runs.node_wall_sum_ms.median,
      ratio(r.every_node_runs.node_wall_sum_ms.median, copy_ms), r.cached.node_wall_sum_ms.median,
      ratio(r.cached.node_wall_sum_ms.median, copy_ms));
  std::fprintf(out, "copy_passes_per_frame = %.2f\n", r.copy_passes_per_frame());
  if (r.baseline) {
    const SideBySide& b = *r.baseline;
    std::fprintf(out,
                 "against %s (frames alternated in this run, static nodes cached): %.3f ms / "
                 "%.3f ms = %.2f; per pair of frames %.2f [%.2f .. %.2f]\n",
                 r.baseline_graph.c_str(), b.graph_ms.median, b.baseline_ms.median,
                 ratio(b.graph_ms.median, b.baseline_ms.median), b.pair_ratio.median,
                 b.pair_ratio.min, b.pair_ratio.max);
  }

  if (!r.cpu_references)
    std::fprintf(out,
                 "\nno CPU references in this build: node accuracy sweeps skipped "
                 "(reconfigure with -DAQUARELLE_BUILD_REFERENCES=ON)\n");
  for (const auto& sweep : r.sweeps) {
    std::fprintf(out, "\nsweep: %s (%s)\n  reference: %s\n", sweep.series.c_str(),
                 sweep.kind.c_str(), sweep.reference.c_str());
    if (!sweep.note.empty()) std::fprintf(out, "  note: %s\n", sweep.note.c_str());
    const auto front = pareto_points(sweep);
    std::fprintf(out, "  %-26s %-6s %12s %11s %11s %8s\n", "setting", "prec.",
                 (sweep.time_measure == "frame wall" ? "frame ms" : "wall ms"), "max abs",
                 "mean abs", "PSNR");
    for (size_t i = 0; i < sweep.points.size(); ++i) {
      const auto& p = sweep.points[i];
      const bool pareto = std::find(front.begin(), front.end(), i) != front.end();
      std::fprintf(out, "  %-26s %-6s %12.3f %11.3g %11.3g %8.2f%s%s\n", p.setting.c_str(),
                   p.precision.c_str(), p.time_ms.median, p.error.max_abs, p.error.mean_abs,
                   p.error.psnr, pareto ? "  *" : "", p.is_reference ? "  (reference)" : "");
    }
  }
  if (!r.sweeps.empty()) std::fprintf(out, "\n* Pareto point (no faster point is as exact)\n");
}

Status write_report_csv(const BenchReport& r, const std::string& path) {
  const std::string temporary = path + ".tmp-" + std::to_string(getpid());
  {
    std::ofstream out(temporary);
    if (!out) return make_error("cannot write '" + path + "': is the folder there and writable?");
    out << "section,series,node,type,setting,precision,time_ms_median,time_ms_min,time_ms_q1,"
           "time_ms_q3,time_ms_max,timestamp_ms_median,runs,max_abs,mean_abs,psnr,is_"
           "reference,"
           "pareto,reference\n";
    auto row = [&](const std::string& section, const std::string& series, const std::string& node,
                   const std::string& type, const std::string& setting,
                   const std::string& precision, const Spread& time, double timestamp_ms,
                   const std::string& runs, const std::string& max_abs, const std::string& mean_abs,
                   const std::string& psnr, const std::string& is_reference,
                   const std::string& pareto, const std::string& reference) {
      out << csv_field(section) << ',' << csv_field(series) << ',' << csv_field(node) << ','
          << csv_field(type) << ',' << csv_field(setting) << ',' << precision << ','
          << csv_number(time.median) << ',' << csv_number(time.min) << ',' << csv_number(time.q1)
          << ',' << csv_number(time.q3) << ',' << csv_number(time.max) << ','
          << csv_number(timestamp_ms) << ',' << runs << ',' << max_abs << ',' << mean_abs << ','
          << psnr << ',' << is_reference << ',' << pareto << ',' << csv_field(reference) << '\n';
    };
    row("copy_pass", "", "", "", "", r.precision, r.copy_pass.wall_ms,
        r.copy_pass.timestamp_ms.median, std::to_string(r.copy_pass.wall_ms.count), "", "", "", "",
        "", "");
    for (const auto* timing : {&r.every_node_runs, &r.cached}) {
      const std::string mode = timing->static_cached ? "cached_static_nodes" : "every_node_runs";
      for (const auto& n : timing->nodes) {
        const auto e = r.node_errors.find(n.id);
        const bool has_error = e != r.node_errors.end();
        const ErrorStats error = has_error ? e->second.error : ErrorStats{};
        row("node", mode, n.id, n.type, has_error ? e->second.against : "", r.precision, n.wall_ms,
            n.gpu_ms.median, std::to_string(n.runs), has_error ? csv_number(error.max_abs) : "",
            has_error ? csv_number(error.mean_abs) : "", has_error ? csv_number(error.psnr) : "",
            "", "", has_error ? "exact node: " + e->second.against : "");
      }
      row("frame", mode, "", "", "", r.precision, timing->frame_ms, 0.0, "", "", "", "", "", "",
          "");
    }
    for (const auto& sweep : r.sweeps) {
      const auto front = pareto_points(sweep);
      for (size_t i = 0; i < sweep.points.size(); ++i) {
        const auto& p = sweep.points[i];
        const bool pareto = std::find(front.begin(), front.end(), i) != front.end();
        row("sweep", sweep.series, "", sweep.node_type, p.setting, p.precision, p.time_ms,
            p.gpu_ms.median, "", csv_number(p.error.max_abs), csv_number(p.error.mean_abs),
            csv_number(p.error.psnr), p.is_reference ? "1" : "0", pareto ? "1" : "0",
            sweep.kind + ": " + sweep.reference);
      }
    }
    out.flush();
    if (!out) {
      std::error_code ec;
      std::filesystem::remove(temporary, ec);
      return make_error("writing '" + path + "' failed (disk full?)");
    }
  }
  std::error_code ec;
  std::filesystem::rename(temporary, path, ec);
  if (ec) {
    std::filesystem::remove(temporary, ec);
    return make_error("cannot write '" + path + "': " + ec.message());
  }
  return Ok{};
}

Status check_bench_outputs(const Graph* graph, const Registry& registry, const std::string& csv,
                           const std::string& plot, const std::string& plot_from) {
  std::vector<ReadFile> reads;
  if (graph != nullptr) reads = files_read_by(*graph, registry);
  if (!plot_from.empty()) reads.push_back({plot_from, "the report --plot-from reads"});
  if (!csv.empty()) {
    if (auto s = check_may_write("--csv", csv, reads); !s.ok()) return s;
  }
  if (!plot.empty()) {
    if (auto s = check_may_write("--plot", plot, reads); !s.ok()) return s;
    if (!csv.empty() && check_may_write("--plot", plot, {{csv, "--csv"}}).ok() == false) {
      return make_error("--plot and --csv name the same file " + quote_for_message(plot) +
                        ": give each its own");
    }
  }
  return Ok{};
}

Result<nlohmann::json> read_report_file(const std::string& path) {
  constexpr uint64_t kMaxReportBytes = 64ull << 20;
  std::string text, why;
  if (!files::read_regular_file(path, kMaxReportBytes, &text, &why)) {
    return make_error("--plot-from " + quote_for_message(path) + ": " + why);
  }
  nlohmann::json report = nlohmann::json::parse(text, nullptr, false);
  if (report.is_discarded()) {
    return make_error("--plot-from " + quote_for_message(path) + ": cannot read it as JSON");
  }
  return report;
}

}  // namespace aq::app
