// The sweeps of `aquarelle bench` for the layered watercolor (graphs/layered.json,
// graphs/three_cubes.json) and pigment mixing, against the double CPU references:
//
//   layered ids      the `layered` node on synthetic g-buffers of N objects (N = 1 .. 64; a
//                    grid of large discs, small scattered discs, small discs over a floor):
//                    cost against N, error against reference::layered; and the abstraction
//                    sigma at 16 objects
//   pigment chart    `pigment_mix` on a colour chart (pigment pairs across, mixing ratio 0 .. 1
//                    up) in rgb, cmyk and kubelka_munk against reference::pigment_mix; the
//                    note gives what each mode makes of the chart's pairs at ratio ½
//                    (blue + yellow: grey as light and CMYK, green as Kubelka–Munk pigments)
#include <chrono>
#include <cmath>
#include <cstdio>
#include <map>
#include <memory>

#include "bench_reference_configs.h"
#include "bench_sweep.h"

#ifdef AQ_HAVE_CPU_REFERENCES
#include "aquarelle/reference/layered.h"
#include "aquarelle/reference/pigment_mix.h"
#endif

namespace aq::app {

#ifndef AQ_HAVE_CPU_REFERENCES

Result<std::vector<Sweep>> run_layered_sweeps(GlContext&, const Registry&, const Graph&,
                                              const SweepPlan&, const std::set<std::string>&) {
  return std::vector<Sweep>{};
}

#else

namespace {

struct GBufferImages {
  ImageF id, normal, albedo, depth;
};

// Where the synthetic objects lie: `grid` fills the frame with discs as large as the cells,
// `scattered` puts small discs (radius 2 % of the short side) at the cell centres, jittered,
// `floor` puts the same small discs over a full-screen floor object behind them.
enum class Layout { kGrid, kScattered, kFloor };

void set_pixel(GBufferImages& g, int x, int y, float id, const float normal[3], const float rgb[3],
               float depth) {
  const float values[4][4] = {{id, 0, 0, 1},
                              {normal[0], normal[1], normal[2], 1},
                              {rgb[0], rgb[1], rgb[2], 1},
                              {depth, 0, 0, 1}};
  ImageF* images[4] = {&g.id, &g.normal, &g.albedo, &g.depth};
  for (int k = 0; k < 4; ++k)
    for (int c = 0; c < 4; ++c) images[k]->at(x, y, c) = values[k][c];
}

// `count` objects (sphere normals, depth growing with the index, colours spread over the hue
// circle), laid out as `layout` says.
GBufferImages synthetic_gbuffer(int w, int h, int count, Layout layout = Layout::kGrid) {
  GBufferImages g{ImageF(w, h, 4, 0.0f), ImageF(w, h, 4, 0.0f), ImageF(w, h, 4, 0.0f),
                  ImageF(w, h, 4, 0.0f)};
  const int columns = std::max(1, static_cast<int>(std::ceil(std::sqrt(count * double(w) / h))));
  const int rows = (count + columns - 1) / columns;
  const double cw = double(w) / columns, ch = double(h) / rows;
  const bool small = layout != Layout::kGrid;
  const double radius = small ? std::max(2.0, 0.02 * std::min(w, h)) : 0.45 * std::min(cw, ch);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      if (layout == Layout::kFloor) {
        const float up[3] = {0.0f, 0.7071f, 0.7071f}, sand[3] = {0.8f, 0.7f, 0.5f};
        set_pixel(g, x, y, static_cast<float>(count + 1), up, sand, 20.0f);
      }
      const int cx = std::min(columns - 1, static_cast<int>(x / cw));
      const int cy = std::min(rows - 1, static_cast<int>(y / ch));
      const int index = cy * columns + cx;
      // Scattered discs sit off their cell centre by up to a quarter cell (a fixed hash).
      const double jx = small ? 0.25 * std::sin(12.9898 * index) * (cw - 2 * radius) : 0.0;
      const double jy = small ? 0.25 * std::cos(78.233 * index) * (ch - 2 * radius) : 0.0;
      const double dx = (x + 0.5 - (cx + 0.5) * cw - jx) / radius;
      const double dy = (y + 0.5 - (cy + 0.5) * ch - jy) / radius;
      const double d2 = dx * dx + dy * dy;
      if (index >= count || d2 >= 1.0) continue;
      const double nz = std::sqrt(1.0 - d2);
      const double hue = 6.283185 * index / std::max(count, 1);
      const float normal[3] = {static_cast<float>(dx), static_cast<float>(dy),
                               static_cast<float>(nz)};
      const float rgb[3] = {static_cast<float>(0.5 + 0.4 * std::cos(hue)),
                            static_cast<float>(0.5 + 0.4 * std::cos(hue - 2.094)),
                            static_cast<float>(0.5 + 0.4 * std::cos(hue + 2.094))};
      set_pixel(g, x, y, static_cast<float>(index + 1), normal, rgb,
                static_cast<float>(2.0 + 0.1 * index - 0.3 * nz));
    }
  return g;
}

Result<Sweep> layered_ids_sweep(GlContext& context, const Registry& registry,
                                const SweepPlan& plan) {
  const int w = plan.width, h = plan.height;
  Sweep sweep = cpu_sweep(
      "layered ids", "layered",
      "reference::layered in double (segmentation, lighting, abstraction, wet edges, glazing) "
      "on a synthetic g-buffer of N sphere objects (grid: discs filling the frame; scattered: "
      "small discs; floor: small discs over a full-screen floor); highlights off (a step)");
  sweep.note =
      "objects whose reach cannot meet share an RGBA channel, so the cost follows how many "
      "layers pile up on one spot (ceil(channels/4) ranges of 11 passes), not N; plus one "
      "readback of id, depth and albedo per frame";
  reference::LayeredParams params;
  params.specular_threshold = 1.0;
  Status measured = Ok{};
  auto add = [&](int count, double sigma, Layout layout, const char* name) {
    if (!measured.ok()) return;
    const GBufferImages g = synthetic_gbuffer(w, h, count, layout);
    reference::LayeredParams p = params;
    p.abstraction_sigma = sigma;
    auto exact = timed_reference(&sweep.reference_ms, [&] {
      return reference::layered(g.id, g.normal, g.albedo, g.depth, nullptr, p);
    });
    char setting[64];
    std::snprintf(setting, sizeof setting, "%s ids=%d sigma=%g", name, count, sigma);
    std::vector<ReferenceConfig> configs;
    for (const char* precision : {"half", "float"}) {
      configs.push_back(
          {setting, {{"specular_threshold", 1.0}, {"abstraction_sigma", sigma}}, precision, exact});
    }
    measured =
        run_configs(context, registry, plan, "layered", nlohmann::json::object(),
                    {{"id", "id"}, {"normal", "normal"}, {"albedo", "albedo"}, {"depth", "depth"}},
                    {{"id", g.id}, {"normal", g.normal}, {"albedo", g.albedo}, {"depth", g.depth}},
                    configs, w, h, &sweep);
  };
  for (int count : {1, 4, 16, 64}) add(count, 3.0, Layout::kGrid, "grid");
  for (int count : {4, 16, 64}) add(count, 3.0, Layout::kScattered, "scattered");
  for (int count : {4, 16, 64}) add(count, 3.0, Layout::kFloor, "floor");
  for (double sigma : {1.5, 6.0}) add(16, sigma, Layout::kGrid, "grid");
  if (!measured.ok()) return measured.error();
  return sweep;
}

using reference::PigmentPair;
constexpr const auto& kChart = reference::kPigmentChart;

Result<Sweep> pigment_chart_sweep(GlContext& context, const Registry& registry,
                                  const SweepPlan& plan) {
  // The chart: one column per pair, the ratio (b's alpha) rising from 0 at the bottom to 1.
  const int pairs = static_cast<int>(std::size(kChart));
  const int w = pairs * 16, h = 64;
  ImageF a(w, h, 4, 1.0f), b(w, h, 4, 1.0f);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const PigmentPair& pair = kChart[x / 16];
      for (int c = 0; c < 3; ++c) {
        a.at(x, y, c) = static_cast<float>(pair.a[c]);
        b.at(x, y, c) = static_cast<float>(pair.b[c]);
      }
      b.at(x, y, 3) = static_cast<float>(y) / (h - 1);
    }
  Sweep sweep = cpu_sweep("pigment chart", "pigment_mix",
                          "reference::pigment_mix in double on a colour chart of 7 pigment "
                          "pairs, ratio 0..1");
  std::string note = "at ratio 1/2:";
  std::vector<ReferenceConfig> configs;
  const char* names[] = {"rgb", "cmyk", "kubelka_munk"};
  const reference::MixMode modes[] = {reference::MixMode::kRgb, reference::MixMode::kCmyk,
                                      reference::MixMode::kKubelkaMunk};
  for (int m = 0; m < 3; ++m) {
    auto exact = timed_reference(&sweep.reference_ms,
                                 [&] { return reference::pigment_mix(a, b, 1.0, modes[m]); });
    for (const char* precision : {"half", "float"}) {
      configs.push_back({std::string("mode=") + names[m],
                         {{"mode", names[m]}, {"factor", 1.0}},
                         precision,
                         exact});
    }
    note += std::string(" ") + names[m] + " {";
    for (const PigmentPair& pair : kChart) {
      const reference::Rgb c = reference::mix(pair.a, pair.b, 0.5, modes[m]);
      char text[96];
      std::snprintf(text, sizeof text, "%s (%.2f %.2f %.2f)%s", pair.name, c[0], c[1], c[2],
                    &pair == &kChart[pairs - 1] ? "" : ", ");
      note += text;
    }
    note += "}";
  }
  sweep.note = note;
  if (auto s = run_configs(context, registry, plan, "pigment_mix", nlohmann::json::object(),
                           {{"a", "a"}, {"b", "b"}}, {{"a", a}, {"b", b}}, configs, w, h, &sweep);
      !s.ok()) {
    return s.error();
  }
  return sweep;
}

}  // namespace

Result<std::vector<Sweep>> run_layered_sweeps(GlContext& context, const Registry& registry,
                                              const Graph&, const SweepPlan& plan,
                                              const std::set<std::string>& types) {
  std::vector<Sweep> sweeps;
  const bool layered = types.count("layered") > 0 && registry.find("layered") != nullptr;
  const bool mixing =
      (layered || types.count("pigment_mix") > 0) && registry.find("pigment_mix") != nullptr;
  if (layered) {
    auto sweep = layered_ids_sweep(context, registry, plan);
    if (!sweep.ok()) return sweep.error();
    sweeps.push_back(*sweep);
  }
  if (mixing) {
    auto sweep = pigment_chart_sweep(context, registry, plan);
    if (!sweep.ok()) return sweep.error();
    sweeps.push_back(*sweep);
  }
  return sweeps;
}

#endif  // AQ_HAVE_CPU_REFERENCES

}  // namespace aq::app
