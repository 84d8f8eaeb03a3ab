// Speed-against-error plot of `aquarelle bench` with PLplot (see bench_plot.h). The page is a
// grid of panels in normalised device coordinates; each panel has its own decade-rounded log
// ranges, since node times and errors span very different decades.
#include "bench_plot.h"

#include <plplot.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <limits>
#include <map>

namespace aq::app {

namespace {

// Colour map 0: background, ink, grid, then the curves (Okabe-Ito).
enum ColorIndex { kBackground = 0, kInk = 1, kGrid = 2, kFirstCurve = 3 };
constexpr int kPalette[][3] = {{255, 255, 255}, {0, 0, 0},     {215, 215, 215},
                               {0, 114, 178},   {230, 159, 0}, {0, 158, 115},
                               {204, 121, 167}, {213, 94, 0},  {86, 180, 233}};
constexpr int kCurveColors = static_cast<int>(std::size(kPalette)) - kFirstCurve;

// Text sizes below are fractions of kTextPixels; g_text_factor converts them to PLplot's
// character scale for the page being drawn (set after plinit).
constexpr double kTextPixels = 22.0;
double g_text_factor = 1.0;
void text_size(double scale) {
  plschr(0, scale * g_text_factor);
}

constexpr const char* kHollow = "○";
constexpr const char* kFilled = "●";

struct Panel {
  std::string node;
  std::vector<const Sweep*> sweeps;
};

std::vector<Panel> panels_by_node(const std::vector<Sweep>& sweeps) {
  std::vector<Panel> panels;
  for (const auto& sweep : sweeps) {
    const std::string node = sweep.node_type.empty() ? sweep.series : sweep.node_type;
    auto it =
        std::find_if(panels.begin(), panels.end(), [&](const Panel& p) { return p.node == node; });
    if (it == panels.end()) {
      panels.push_back({node, {}});
      it = panels.end() - 1;
    }
    it->sweeps.push_back(&sweep);
  }
  return panels;
}

bool plottable(const SweepPoint& p) {
  return p.time_ms.median > 0 && std::isfinite(p.time_ms.median) &&
         std::isfinite(p.error.mean_abs) && p.error.mean_abs >= 0;
}

// Decade-rounded log10 ranges of a panel; exact points (error 0) get the decade below the
// smallest error.
struct Ranges {
  double t0 = -1, t1 = 1, e0 = -4, e1 = -1;
  bool any_exact = false;
};

Ranges panel_ranges(const Panel& panel) {
  double min_t = std::numeric_limits<double>::infinity(), max_t = 0;
  double min_e = std::numeric_limits<double>::infinity(), max_e = 0;
  Ranges r;
  for (const Sweep* sweep : panel.sweeps) {
    for (const auto& p : sweep->points) {
      if (!plottable(p)) continue;
      min_t = std::min(min_t, p.time_ms.median);
      max_t = std::max(max_t, p.time_ms.median);
      if (p.error.mean_abs > 0) {
        min_e = std::min(min_e, p.error.mean_abs);
        max_e = std::max(max_e, p.error.mean_abs);
      } else {
        r.any_exact = true;
      }
    }
  }
  if (max_t > 0) {
    // A margin of 0.15 decades keeps points off the frame.
    r.t0 = std::floor(std::log10(min_t) - 0.15);
    r.t1 = std::max(r.t0 + 1, std::ceil(std::log10(max_t) + 0.15));
  }
  if (max_e > 0) {
    r.e0 = std::floor(std::log10(min_e));
    r.e1 = std::max(r.e0 + 1, std::ceil(std::log10(max_e) + 0.15));
  }
  if (r.any_exact) r.e0 -= 1;
  return r;
}

void draw_panel(const Panel& panel, const Ranges& r, double x0, double x1, double y0, double y1,
                int first_color) {
  plvpor(x0, x1, y0, y1);
  plwind(r.t0, r.t1, r.e0, r.e1);
  // At most about five labelled decades per axis; minor ticks (2..9) only when every decade is
  // labelled.
  const double x_step = std::max(1.0, std::ceil((r.t1 - r.t0) / 4));
  const double y_step = std::max(1.0, std::ceil((r.e1 - r.e0) / 5));
  const std::string x_options = x_step == 1 ? "bcnstl" : "bcntl";
  const std::string y_options = y_step == 1 ? "bcnstvl" : "bcntvl";
  plcol0(kGrid);
  plwidth(0.5);
  plbox(x_step == 1 ? "gh" : "g", x_step, 0, y_step == 1 ? "gh" : "g", y_step, 0);
  plcol0(kInk);
  plwidth(1.0);
  text_size(0.55);
  plbox(x_options.c_str(), x_step, 0, y_options.c_str(), y_step, 0);
  if (r.any_exact) {
    text_size(0.5);
    plptex(r.t0 + 0.02 * (r.t1 - r.t0), r.e0 + 0.035 * (r.e1 - r.e0), 1, 0, 0, "exact (0)");
  }
  text_size(0.75);
  plmtex("t", 1.0, 0.5, 0.5, panel.node.c_str());
  text_size(0.55);
  plmtex("b", 3.2, 0.5, 0.5, "time (ms)");
  plmtex("l", 4.2, 0.5, 0.5, "mean abs error");

  std::vector<std::string> labels;
  std::vector<int> colors;
  for (size_t s = 0; s < panel.sweeps.size(); ++s) {
    const Sweep& sweep = *panel.sweeps[s];
    const int color = kFirstCurve + (first_color + static_cast<int>(s)) % kCurveColors;
    auto y_of = [&](double error) { return error > 0 ? std::log10(error) : r.e0; };
    plcol0(color);
    text_size(0.7);
    for (const auto& p : sweep.points) {
      if (!plottable(p)) continue;
      PLFLT x = std::log10(p.time_ms.median), y = y_of(p.error.mean_abs);
      plstring(1, &x, &y, kHollow);
    }
    std::vector<PLFLT> xs, ys;
    for (size_t i : pareto_points(sweep)) {
      const auto& p = sweep.points[i];
      if (!plottable(p)) continue;
      xs.push_back(std::log10(p.time_ms.median));
      ys.push_back(y_of(p.error.mean_abs));
    }
    plwidth(1.5);
    if (xs.size() > 1) plline(static_cast<PLINT>(xs.size()), xs.data(), ys.data());
    if (!xs.empty()) plstring(static_cast<PLINT>(xs.size()), xs.data(), ys.data(), kFilled);
    plwidth(1.0);
    labels.push_back(sweep.series);
    colors.push_back(color);
  }

  // Legend inside the panel, in the corner where it covers the fewest points (its size
  // estimated from the labels, as fractions of the panel).
  size_t longest = 0;
  for (const Sweep* sweep : panel.sweeps) longest = std::max(longest, sweep->series.size());
  const double legend_w = std::min(0.95, 0.1 + 0.028 * static_cast<double>(longest));
  const double legend_h = 0.05 + 0.075 * static_cast<double>(panel.sweeps.size());
  PLINT corner = PL_POSITION_TOP | PL_POSITION_RIGHT;
  int fewest = std::numeric_limits<int>::max();
  for (PLINT candidate :
       {PL_POSITION_TOP | PL_POSITION_RIGHT, PL_POSITION_TOP | PL_POSITION_LEFT,
        PL_POSITION_BOTTOM | PL_POSITION_LEFT, PL_POSITION_BOTTOM | PL_POSITION_RIGHT}) {
    int inside = 0;
    for (const Sweep* sweep : panel.sweeps) {
      for (const auto& p : sweep->points) {
        if (!plottable(p)) continue;
        const double u = (std::log10(p.time_ms.median) - r.t0) / (r.t1 - r.t0);
        const double v =
            ((p.error.mean_abs > 0 ? std::log10(p.error.mean_abs) : r.e0) - r.e0) / (r.e1 - r.e0);
        const bool right = (candidate & PL_POSITION_RIGHT) != 0;
        const bool top = (candidate & PL_POSITION_TOP) != 0;
        if ((right ? u > 1 - legend_w : u < legend_w) && (top ? v > 1 - legend_h : v < legend_h)) {
          ++inside;
        }
      }
    }
    if (inside < fewest) {
      fewest = inside;
      corner = candidate;
    }
  }
  const PLINT count = static_cast<PLINT>(labels.size());
  std::vector<const char*> texts, symbols(count, kFilled);
  for (const auto& label : labels) texts.push_back(label.c_str());
  std::vector<PLINT> options(count, PL_LEGEND_LINE | PL_LEGEND_SYMBOL), styles(count, 1),
      symbol_numbers(count, 1);
  std::vector<PLFLT> widths(count, 1.5), symbol_scales(count, 0.6);
  PLFLT legend_width = 0, legend_height = 0;
  text_size(0.5);
  pllegend(&legend_width, &legend_height, PL_LEGEND_BACKGROUND | PL_LEGEND_BOUNDING_BOX,
           corner | PL_POSITION_INSIDE, 0.01, 0.01, 0.05, kBackground, kGrid, 1, 0, 0, count,
           options.data(), 0.5, 0.55 * g_text_factor, 1.6, 0.0, colors.data(), texts.data(),
           nullptr, nullptr, nullptr, nullptr, colors.data(), styles.data(), widths.data(),
           colors.data(), symbol_scales.data(), symbol_numbers.data(), symbols.data());
}

std::string lowercase_extension(const std::string& path) {
  std::string ext = std::filesystem::path(path).extension().string();
  for (auto& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return ext;
}

// Whether this PLplot has a file device (its driver is a separate Debian package).
bool has_device(const std::string& name) {
  const char* menus[128];
  const char* names[128];
  const char** menu_list = menus;
  const char** name_list = names;
  int count = 128;
  plgFileDevs(&menu_list, &name_list, &count);
  for (int i = 0; i < count; ++i) {
    if (name == name_list[i]) return true;
  }
  return false;
}

}  // namespace

std::vector<size_t> pareto_points(const Sweep& sweep) {
  std::vector<size_t> order(sweep.points.size());
  for (size_t i = 0; i < order.size(); ++i) order[i] = i;
  std::sort(order.begin(), order.end(), [&](size_t a, size_t b) {
    const auto& pa = sweep.points[a];
    const auto& pb = sweep.points[b];
    if (pa.time_ms.median != pb.time_ms.median) return pa.time_ms.median < pb.time_ms.median;
    return pa.error.mean_abs < pb.error.mean_abs;
  });
  std::vector<size_t> front;
  double best = std::numeric_limits<double>::infinity();
  for (size_t i : order) {
    const double error = sweep.points[i].error.mean_abs;
    if (error < best) {
      front.push_back(i);
      best = error;
    }
  }
  return front;
}

Status write_plot(const std::vector<Sweep>& sweeps, const std::string& title,
                  const std::string& path) {
  const std::string ext = lowercase_extension(path);
  const std::map<std::string, std::string> devices = {
      {".png", "pngcairo"}, {".svg", "svgcairo"}, {".pdf", "pdfcairo"}};
  auto device = devices.find(ext);
  if (device == devices.end()) {
    return make_error("cannot plot to " + path + ": use a .png, .svg or .pdf file name");
  }
  if (!has_device(device->second)) {
    return make_error("cannot plot to " + path + ": PLplot has no '" + device->second +
                      "' device; install it (apt-get install plplot-driver-cairo)");
  }
  // PLplot ends the process when it cannot open its file: check the folder first. The plot goes
  // to a temporary file that is renamed over PATH, so a reader never sees half of it.
  const std::string temporary = path + ".tmp-" + std::to_string(::getpid()) + ext;
  if (!std::ofstream(temporary)) {
    return make_error("cannot plot to " + path +
                      ": cannot create a file there (does the folder exist, is it writable?)");
  }

  const std::vector<Panel> panels = panels_by_node(sweeps);
  const int count = std::max<int>(1, static_cast<int>(panels.size()));
  const int columns = std::min(count, 4);
  const int rows = (count + columns - 1) / columns;
  const int panel_w = 340, panel_h = 270, title_h = 60;
  const int width = std::max(columns * panel_w, 2 * panel_w), height = rows * panel_h + title_h;

  plsdev(device->second.c_str());
  plsfnam(temporary.c_str());
  plspage(96, 96, width, height, 0, 0);
  plscmap0n(static_cast<PLINT>(std::size(kPalette)));
  for (size_t i = 0; i < std::size(kPalette); ++i) {
    plscol0(static_cast<PLINT>(i), kPalette[i][0], kPalette[i][1], kPalette[i][2]);
  }
  plinit();
  pladv(0);
  {
    // PLplot's default character height grows with the page: scale text to a fixed pixel size.
    PLFLT default_mm = 0, current_mm = 0, x0 = 0, x1 = 0, y0 = 0, y1 = 0;
    plgchr(&default_mm, &current_mm);
    plgspa(&x0, &x1, &y0, &y1);
    const double pixels_per_mm = x1 > x0 ? width / (x1 - x0) : 96 / 25.4;
    g_text_factor = default_mm > 0 ? kTextPixels / (default_mm * pixels_per_mm) : 1.0;
  }

  const double band = static_cast<double>(title_h) / height;
  plvpor(0, 1, 1 - band, 1);
  plwind(0, 1, 0, 1);
  plcol0(kInk);
  text_size(1.0);
  plptex(0.5, 0.62, 1, 0, 0.5, title.c_str());
  text_size(0.7);
  plptex(0.5, 0.22, 1, 0, 0.5, "● Pareto front (nothing faster is as exact)   ○ other settings");

  int color = 0;
  for (int i = 0; i < static_cast<int>(panels.size()); ++i) {
    const int column = i % columns, row = i / columns;
    const double cell_w = 1.0 / columns, cell_h = (1.0 - band) / rows;
    const double x0 = column * cell_w, y1 = (1.0 - band) - row * cell_h;
    draw_panel(panels[i], panel_ranges(panels[i]), x0 + 0.22 * cell_w, x0 + 0.95 * cell_w,
               y1 - cell_h + 0.22 * cell_h, y1 - 0.12 * cell_h, color);
    color += static_cast<int>(panels[i].sweeps.size());
  }
  plend();

  std::error_code ec;
  std::filesystem::rename(temporary, path, ec);
  if (ec) {
    std::filesystem::remove(temporary, ec);
    return make_error("cannot plot to " + path + ": renaming " + temporary + " over it failed");
  }
  return Ok{};
}

Result<std::vector<Sweep>> sweeps_from_report(const nlohmann::json& report) {
  if (!report.is_object() || !report.contains("sweeps") || !report["sweeps"].is_array()) {
    return make_error("not a report of `aquarelle bench --json`: it has no \"sweeps\" array");
  }
  std::vector<Sweep> sweeps;
  for (const auto& s : report["sweeps"]) {
    Sweep sweep;
    sweep.series = s.value("series", "");
    sweep.node_type = s.value("node", "");
    sweep.kind = s.value("kind", "");
    sweep.time_measure = s.value("time_measure", "");
    for (const auto& p : s.value("points", nlohmann::json::array())) {
      SweepPoint point;
      point.setting = p.value("setting", "");
      point.precision = p.value("precision", "");
      if (p.contains("time_ms") && p["time_ms"].is_object()) {
        point.time_ms.median = p["time_ms"].value("median", 0.0);
      }
      // JSON has no infinity: a null error is an unmeasured point.
      point.error.mean_abs = p.value("mean_abs", nlohmann::json()).is_number()
                                 ? p["mean_abs"].get<double>()
                                 : std::numeric_limits<double>::quiet_NaN();
      point.is_reference = p.value("is_reference", false);
      sweep.points.push_back(point);
    }
    sweeps.push_back(std::move(sweep));
  }
  return sweeps;
}

}  // namespace aq::app
