// The node sweeps of `aquarelle bench` that have a CPU reference: each node runs alone on the
// fixed test input at every quality setting and precision, and its output is compared with the
// double-precision implementation in reference/ (see bench_sweep.h).
#include <algorithm>
#include <chrono>
#include <cmath>
#include <memory>

#include "bench_graph_build.h"
#include "bench_reference_configs.h"
#include "bench_sweep.h"

#ifdef AQ_HAVE_CPU_REFERENCES
#include "aquarelle/reference/bleed.h"
#include "aquarelle/reference/blur.h"
#include "aquarelle/reference/caustics_flux_reference.h"
#include "aquarelle/reference/caustics_reference.h"
#include "aquarelle/reference/dilution.h"
#include "aquarelle/reference/edge.h"
#include "aquarelle/reference/edge_darkening.h"
#include "aquarelle/reference/morphology.h"
#include "aquarelle/reference/paper_relief.h"
#include "aquarelle/reference/tint.h"
#include "aquarelle/reference/tremor.h"
#include "aquarelle/reference/vignette.h"
#endif

namespace aq::app {

bool have_cpu_references() {
#ifdef AQ_HAVE_CPU_REFERENCES
  return true;
#else
  return false;
#endif
}

#ifndef AQ_HAVE_CPU_REFERENCES

Result<std::vector<Sweep>> run_reference_sweeps(GlContext&, const Registry&, const Graph&,
                                                const SweepPlan&, const std::set<std::string>&) {
  return std::vector<Sweep>{};
}

#else

namespace {

using json = nlohmann::json;

using Config = ReferenceConfig;

const char* const kPrecisions[] = {"half", "float"};

// Blur, uniform σ (no depth input: strength 1 everywhere) against the exact Gaussian, and
// depth-varying σ against the ideal per-pixel Gaussian.
Result<std::vector<Sweep>> blur_sweeps(GlContext& context, const Registry& registry,
                                       const Graph& graph, const SweepPlan& plan) {
  const int w = plan.width, h = plan.height;
  const double sigma = number(graph_param(graph, registry, "blur", "sigma"), 4.0);
  const std::map<std::string, ImageF> images{{"image", sweep_test_image(w, h)},
                                             {"depth", sweep_depth_image(w, h)}};
  const json methods[] = {{{"method", "gaussian"}, {"linear_taps", true}},
                          {{"method", "gaussian"}, {"linear_taps", false}},
                          {{"method", "strided"}, {"linear_taps", false}}};
  const char* names[] = {"gaussian linear_taps", "gaussian exact_taps", "strided"};
  std::vector<Sweep> sweeps;

  char label[64];
  std::snprintf(label, sizeof(label), "blur sigma=%g", sigma);
  Sweep uniform = cpu_sweep(label, "blur", "reference::gaussian_blur (separable, double, 8 sigma)");
  uniform.reference = "exact Gaussian, double precision (reference::gaussian_blur)";
  auto exact = timed_reference(&uniform.reference_ms,
                               [&] { return reference::gaussian_blur(images.at("image"), sigma); });
  std::vector<Config> configs;
  for (const char* precision : kPrecisions) {
    for (size_t m = 0; m < 3; ++m) configs.push_back({names[m], methods[m], precision, exact});
  }
  const json uniform_params = {{"sigma", sigma}, {"depth_weight", 1.0}, {"radial_weight", 0.0}};
  if (auto s = run_configs(context, registry, plan, "blur", uniform_params, {{"image", "image"}},
                           images, configs, w, h, &uniform);
      !s.ok()) {
    return s.error();
  }
  sweeps.push_back(uniform);

  std::snprintf(label, sizeof(label), "blur depth sigma=%g", sigma);
  Sweep varying = cpu_sweep(label, "blur", "");
  varying.reference =
      "ideal variable blur: each pixel's own exact Gaussian, double precision "
      "(reference::exact_variable_blur) on a depth ramp 0.5..40";
  reference::BlurParams params;
  params.sigma = sigma;
  params.distance_scale = number(graph_param(graph, registry, "blur", "distance_scale"), 20.0);
  params.depth_weight = number(graph_param(graph, registry, "blur", "depth_weight"), 1.0);
  params.radial_weight = number(graph_param(graph, registry, "blur", "radial_weight"), 0.35);
  auto ideal = timed_reference(&varying.reference_ms, [&] {
    return reference::exact_variable_blur(images.at("image"), &images.at("depth"), params);
  });
  configs.clear();
  for (const char* precision : kPrecisions) {
    for (size_t m = 0; m < 3; ++m) configs.push_back({names[m], methods[m], precision, ideal});
  }
  const json varying_params = {{"sigma", params.sigma},
                               {"distance_scale", params.distance_scale},
                               {"depth_weight", params.depth_weight},
                               {"radial_weight", params.radial_weight}};
  if (auto s =
          run_configs(context, registry, plan, "blur", varying_params,
                      {{"image", "image"}, {"depth", "depth"}}, images, configs, w, h, &varying);
      !s.ok()) {
    return s.error();
  }
  sweeps.push_back(varying);

  // The one-pass kernels for a small varying sigma at the preview's render scale (half the
  // graph's sigma in working pixels): all 25 taps, or the 17-tap pinwheel the proxy presets use.
  reference::BlurParams small = params;
  small.sigma = 0.5 * sigma;
  std::snprintf(label, sizeof(label), "blur depth sigma=%g", small.sigma);
  Sweep one_pass = cpu_sweep(label, "blur", "");
  one_pass.reference = varying.reference;
  auto small_ideal = timed_reference(&one_pass.reference_ms, [&] {
    return reference::exact_variable_blur(images.at("image"), &images.at("depth"), small);
  });
  configs.clear();
  for (const char* precision : kPrecisions) {
    for (const char* kernel : {"full", "pinwheel"}) {
      configs.push_back({std::string("direct_kernel ") + kernel,
                         {{"method", "gaussian"}, {"direct_kernel", kernel}},
                         precision,
                         small_ideal});
    }
  }
  json small_params = varying_params;
  small_params["sigma"] = small.sigma;
  if (auto s =
          run_configs(context, registry, plan, "blur", small_params,
                      {{"image", "image"}, {"depth", "depth"}}, images, configs, w, h, &one_pass);
      !s.ok()) {
    return s.error();
  }
  sweeps.push_back(one_pass);

  // A wide uniform blur, exact against the reduced-resolution pyramid (blur at a lower level
  // of 2x2 means with the variance corrected, then upsampled).
  constexpr double kWideSigma = 12.0;
  std::snprintf(label, sizeof(label), "blur wide sigma=%g", kWideSigma);
  Sweep wide = cpu_sweep(label, "blur", "");
  wide.reference = "exact Gaussian, double precision (reference::gaussian_blur)";
  auto wide_exact = timed_reference(
      &wide.reference_ms, [&] { return reference::gaussian_blur(images.at("image"), kWideSigma); });
  configs.clear();
  const json full_size = {{"method", "gaussian"}, {"reduced_resolution", false}};
  const json pyramid = {{"method", "gaussian"}, {"reduced_resolution", true}};
  for (const char* precision : kPrecisions) {
    configs.push_back({"full resolution", full_size, precision, wide_exact});
    configs.push_back({"reduced_resolution", pyramid, precision, wide_exact});
  }
  const json wide_params = {{"sigma", kWideSigma}, {"depth_weight", 1.0}, {"radial_weight", 0.0}};
  if (auto s = run_configs(context, registry, plan, "blur", wide_params, {{"image", "image"}},
                           images, configs, w, h, &wide);
      !s.ok()) {
    return s.error();
  }
  sweeps.push_back(wide);
  return sweeps;
}

// The caustic texture size the graph's caustics node renders at the sweep's size (its footprint
// on screen when a scene is connected, after the quality preset's render scale), or
// `fallback` when the graph has no caustics node.
Result<int> graph_caustic_size(GlContext& context, const Registry& registry, const Graph& graph,
                               const SweepPlan& plan, int fallback) {
  const std::string id = first_node_of_type(graph, "caustics");
  if (id.empty()) return fallback;
  Graph sized = graph;
  sized.settings.width = plan.width;
  sized.settings.height = plan.height;
  Evaluator evaluator(context, registry);
  EvalOptions options;
  options.frame = sized.settings.first_frame;
  auto texture = evaluator.evaluate(sized, options, PortRef{id, "image"});
  if (!texture.ok()) return make_error("caustic texture size: " + texture.message());
  return (*texture)->image.width;
}

// The finest grid of the converged reference: at least 8 cells per texel (its error, printed,
// is then far below the estimators'), a power of two between 1024 and 4096.
int reference_grid(int resolution) {
  int grid = 1024;
  while (grid < 8 * resolution && grid < 4096) grid *= 2;
  return grid;
}

// Caustics: the grid of both estimators (coverage, and Stam's point sampling) at the texture
// size the graph renders, against the exact box-filtered flux per texel (converged in double,
// with its own error estimated from three grids).
Result<std::vector<Sweep>> caustics_sweeps(GlContext& context, const Registry& registry,
                                           const Graph& graph, const SweepPlan& plan) {
  constexpr int kWithoutCausticsNode = 128;
  auto size = graph_caustic_size(context, registry, graph, plan, kWithoutCausticsNode);
  if (!size.ok()) return size.error();
  const int resolution = *size;
  reference::CausticsParams p = caustics_params_of(graph, registry, resolution);
  p.time = 0.0;  // the graph's first frame

  const int finest = reference_grid(resolution);
  double reference_ms = 0.0;
  reference::CausticConvergence convergence;
  auto converged = timed_reference(&reference_ms, [&] {
    convergence = reference::converge_caustic_flux(p, finest, 3);
    return reference::to_caustic_image(convergence.texels, resolution);
  });
  char text[512];
  std::snprintf(text, sizeof(text),
                "exact box-filtered flux per texel (reference::converge_caustic_flux: each "
                "refracted triangle's light shared by exact area of overlap) on a %dx%d grid in "
                "double precision, texture %dx%d (the graph's caustic texture at %dx%d)",
                finest, finest, resolution, resolution, plan.width, plan.height);
  const std::string reference_text = text;
  std::snprintf(text, sizeof(text),
                "reference's own error: grids %d, %d, %d differ by RMS %.2e then %.2e (mean abs "
                "%.2e, %.2e), order %.2f, so the %d grid is within RMS %.1e (PSNR %.1f dB) and "
                "mean abs %.1e of the limit (Richardson)",
                convergence.grids[0], convergence.grids[1], convergence.grids[2],
                convergence.rms_steps[0], convergence.rms_steps[1], convergence.mean_abs_steps[0],
                convergence.mean_abs_steps[1], convergence.order, finest, convergence.rms_error,
                -20.0 * std::log10(convergence.rms_error), convergence.mean_abs_error);
  const std::string note = text;

  const json base = {
      {"resolution", resolution},        {"depth", p.depth}, {"amplitude", p.amplitude},
      {"wave_scale", p.wave_scale},      {"speed", p.speed}, {"eta", p.eta},
      {"max_intensity", p.max_intensity}};
  const std::string precision = graph.settings.precision;
  struct Estimator {
    const char* name;
    std::vector<int> grids;
    json params;
  };
  const json normalize = graph_param(graph, registry, "caustics", "normalize_energy");
  const Estimator estimators[] = {
      {"coverage", {32, 64, 96, 128, 192, 256, 384}, {{"estimator", "coverage"}}},
      {"point",
       {32, 64, 128, 256, 512},
       {{"estimator", "point"},
        {"normalize_energy", normalize.is_boolean() ? normalize.get<bool>() : true}}}};
  std::vector<Sweep> sweeps;
  for (const auto& estimator : estimators) {
    Sweep sweep = cpu_sweep(std::string("caustics ") + estimator.name, "caustics", reference_text);
    sweep.note = note;
    sweep.reference_ms = reference_ms;
    json params = base;
    for (const auto& [name, value] : estimator.params.items()) params[name] = value;
    std::vector<Config> configs;
    for (int grid : estimator.grids) {
      configs.push_back({"grid=" + std::to_string(grid), {{"grid", grid}}, precision, converged});
    }
    if (auto s = run_configs(context, registry, plan, "caustics", params, {}, {}, configs,
                             plan.width, plan.height, &sweep);
        !s.ok()) {
      return s.error();
    }
    sweeps.push_back(sweep);
  }
  return sweeps;
}

// Erode or dilate: window size and footprint against flat morphology by definition.
Result<Sweep> morphology_sweep(GlContext& context, const Registry& registry, const Graph& graph,
                               const SweepPlan& plan, const std::string& type) {
  const int w = plan.width, h = plan.height;
  const std::map<std::string, ImageF> images{{"image", sweep_test_image(w, h)}};
  const json mode = graph_param(graph, registry, type, "mode");
  reference::MorphologyParams params;
  params.op = type == "erode" ? reference::MorphologyOp::kErode : reference::MorphologyOp::kDilate;
  params.order = mode == "luminance" ? reference::MorphologyOrder::kLuminance
                                     : reference::MorphologyOrder::kPerChannel;
  Sweep sweep = cpu_sweep(type, type,
                          "flat morphology by definition (reference::morphology): min/max over "
                          "every pixel of the footprint, borders clamped");
  std::vector<Config> configs;
  for (const char* footprint : {"square", "disc"}) {
    for (int size : {3, 5, 9}) {
      params.size = size;
      params.footprint = std::string(footprint) == "disc" ? reference::MorphologyFootprint::kDisc
                                                          : reference::MorphologyFootprint::kSquare;
      auto exact = timed_reference(
          &sweep.reference_ms, [&] { return reference::morphology(images.at("image"), params); });
      for (const char* precision : kPrecisions) {
        configs.push_back({std::string(footprint) + " size=" + std::to_string(size),
                           {{"size", size}, {"footprint", footprint}},
                           precision,
                           exact});
      }
    }
  }
  if (auto s = run_configs(context, registry, plan, type, {{"mode", mode}}, {{"image", "image"}},
                           images, configs, w, h, &sweep);
      !s.ok()) {
    return s.error();
  }
  return sweep;
}

// A pointwise node with no quality setting but precision: half against float, both against
// the reference.
template <typename Reference>
Result<Sweep> precision_sweep(GlContext& context, const Registry& registry, const SweepPlan& plan,
                              const std::string& type, const json& params,
                              const std::string& reference_name, Reference&& compute) {
  const int w = plan.width, h = plan.height;
  const std::map<std::string, ImageF> images{{"image", sweep_test_image(w, h)}};
  Sweep sweep = cpu_sweep(type, type, reference_name);
  auto exact = timed_reference(&sweep.reference_ms, [&] { return compute(images.at("image")); });
  std::vector<Config> configs;
  for (const char* precision : kPrecisions) configs.push_back({"default", {}, precision, exact});
  if (auto s = run_configs(context, registry, plan, type, params, {{"image", "image"}}, images,
                           configs, w, h, &sweep);
      !s.ok()) {
    return s.error();
  }
  return sweep;
}

json vec3_or(const json& value, const json& fallback) {
  return value.is_array() && value.size() == 3 ? value : fallback;
}

// ---- Seed 002 (MNPR) nodes -------------------------------------------------------------

// A control map, depth and id for the bleed sweep: four vertical bands of objects (ids 1..4,
// nearer to the right), bleeding 1, 0.5, 0, 0.8.
struct BleedInputs {
  ImageF control, depth, id;
};
BleedInputs bleed_inputs(int w, int h) {
  BleedInputs in{ImageF(w, h, 4, 0.0f), ImageF(w, h, 1), ImageF(w, h, 1)};
  const float bleeds[4] = {1.0f, 0.5f, 0.0f, 0.8f};
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const int band = std::min(4 * x / std::max(w, 1), 3);
      in.control.at(x, y, 0) = bleeds[band];
      in.depth.at(x, y, 0) = 10.0f - 2.0f * band;
      in.id.at(x, y, 0) = static_cast<float>(band + 1);
    }
  return in;
}

// Bleed: kernel reach (radius in sigmas; 0.5 is the seed's 21x21 at sigma 20) against the same
// gated separable operator at reach 4 in double precision.
Result<Sweep> bleed_sweep(GlContext& context, const Registry& registry, const Graph& graph,
                          const SweepPlan& plan) {
  const int w = plan.width, h = plan.height;
  const BleedInputs in = bleed_inputs(w, h);
  const std::map<std::string, ImageF> images{{"image", sweep_test_image(w, h)},
                                             {"control", in.control},
                                             {"depth", in.depth},
                                             {"id", in.id}};
  reference::BleedParams p;
  p.sigma = number(graph_param(graph, registry, "bleed", "sigma"), p.sigma);
  p.depth_bias = number(graph_param(graph, registry, "bleed", "depth_bias"), p.depth_bias);
  Sweep sweep = cpu_sweep("bleed sigma=" + std::to_string(static_cast<int>(p.sigma)), "bleed",
                          "reference::bleed at reach 4 in double precision (the gated separable "
                          "operator; its difference from a 2D gate is measured in bleed_test)");
  reference::BleedParams exact_params = p;
  exact_params.reach = 4.0;
  auto exact = timed_reference(&sweep.reference_ms, [&] {
    return reference::bleed(images.at("image"), in.control, &in.depth, &in.id, exact_params);
  });
  std::vector<Config> configs;
  for (double reach : {0.5, 1.0, 2.0, 3.0, 4.0}) {
    for (const char* precision : kPrecisions) {
      configs.push_back(
          {"reach=" + std::to_string(reach).substr(0, 3), {{"reach", reach}}, precision, exact});
    }
  }
  if (auto s = run_configs(
          context, registry, plan, "bleed", {{"sigma", p.sigma}, {"depth_bias", p.depth_bias}},
          {{"image", "image"}, {"control", "control"}, {"depth", "depth"}, {"id", "id"}}, images,
          configs, w, h, &sweep);
      !s.ok()) {
    return s.error();
  }
  return sweep;
}

// Edge darkening from the blur difference: sigma (the seed's 3 and around it), each against
// its own double-precision reference (the blur of the SDK truncates at 4 sigma).
Result<Sweep> edge_darkening_sweep(GlContext& context, const Registry& registry, const Graph& graph,
                                   const SweepPlan& plan) {
  const int w = plan.width, h = plan.height;
  const std::map<std::string, ImageF> images{{"image", sweep_test_image(w, h)}};
  reference::EdgeDarkeningParams p;
  p.strength = number(graph_param(graph, registry, "edge_darkening", "strength"), p.strength);
  Sweep sweep = cpu_sweep("edge_darkening", "edge_darkening",
                          "reference::blur_difference_darkening in double precision (untruncated "
                          "Gaussian)");
  std::vector<Config> configs;
  for (double sigma : {1.5, 3.0, 6.0}) {
    p.sigma = sigma;
    auto exact = timed_reference(&sweep.reference_ms, [&] {
      return reference::blur_difference_darkening(images.at("image"), nullptr, nullptr, p);
    });
    for (const char* precision : kPrecisions) {
      configs.push_back(
          {"sigma=" + std::to_string(sigma).substr(0, 3), {{"sigma", sigma}}, precision, exact});
    }
  }
  if (auto s = run_configs(context, registry, plan, "edge_darkening", {{"strength", p.strength}},
                           {{"image", "image"}}, images, configs, w, h, &sweep);
      !s.ok()) {
    return s.error();
  }
  return sweep;
}

// Paper relief and screen-space tremor: precision only (no quality setting).
Result<Sweep> paper_relief_sweep(GlContext& context, const Registry& registry,
                                 const SweepPlan& plan) {
  const int w = plan.width, h = plan.height;
  ImageF paper(w, h, 4, 1.0f);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x)
      paper.at(x, y, 0) = static_cast<float>(0.5 + 0.25 * std::sin(0.7 * x) * std::cos(0.45 * y));
  const std::map<std::string, ImageF> images{{"image", sweep_test_image(w, h)}, {"paper", paper}};
  Sweep sweep = cpu_sweep("paper_relief", "paper_relief", "reference::paper_relief in double");
  auto exact = timed_reference(&sweep.reference_ms, [&] {
    return reference::paper_relief(images.at("image"), paper, nullptr, {});
  });
  std::vector<Config> configs;
  for (const char* precision : kPrecisions) configs.push_back({"default", {}, precision, exact});
  if (auto s = run_configs(context, registry, plan, "paper_relief", json::object(),
                           {{"image", "image"}, {"paper", "paper"}}, images, configs, w, h, &sweep);
      !s.ok()) {
    return s.error();
  }
  return sweep;
}

// Dilution (MNPR's reflectance): the turbulence FBM's octaves, each against the double
// reference at the same octaves, on unit normals turning across the image, the test image as
// albedo and object positions spanning a few FBM cells; the light comes from a scene_join.
Result<Sweep> dilution_sweep(GlContext& context, const Registry& registry, const Graph& graph,
                             const SweepPlan& plan) {
  const int w = plan.width, h = plan.height;
  ImageF normal(w, h, 4, 1.0f), object(w, h, 4, 1.0f);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const double u = 3.0 * (x + 0.5) / w - 1.5, v = 2.0 * (y + 0.5) / h - 1.0;
      const double n[3] = {std::sin(u), std::cos(u) * std::cos(v), std::cos(u) * std::sin(v)};
      for (int c = 0; c < 3; ++c) normal.at(x, y, c) = static_cast<float>(n[c]);
      object.at(x, y, 0) = static_cast<float>(u);
      object.at(x, y, 1) = static_cast<float>(v);
      object.at(x, y, 2) = static_cast<float>(0.3 * u * v);
    }
  const std::map<std::string, ImageF> images{
      {"albedo", sweep_test_image(w, h)}, {"normal", normal}, {"object", object}};
  reference::DilutionParams p;
  const char* names[] = {"dilution", "diffuse_area", "shade", "turbulence", "scale", "cangiante"};
  double* values[] = {&p.dilution,   &p.diffuse_area, &p.shade,
                      &p.turbulence, &p.scale,        &p.cangiante};
  json params = json::object();
  for (size_t i = 0; i < 6; ++i) {
    *values[i] = number(graph_param(graph, registry, "dilution", names[i]), *values[i]);
    params[names[i]] = *values[i];
  }
  const json paper =
      vec3_or(graph_param(graph, registry, "dilution", "paper_color"), {0.96, 0.93, 0.85});
  for (int c = 0; c < 3; ++c) p.paper[c] = paper[c].get<double>();
  params["paper_color"] = paper;
  // The scene_join's default light, as the node sees it (towards the light, unit).
  const double light[3] = {0.7, -1.0, -0.15};
  const double length = std::sqrt(light[0] * light[0] + light[1] * light[1] + light[2] * light[2]);
  for (int c = 0; c < 3; ++c) p.to_light[c] = -light[c] / length;
  Sweep sweep = cpu_sweep("dilution turbulence", "dilution",
                          "reference::dilution in double precision (the same octaves)");
  std::vector<Config> configs;
  for (int octaves : {1, 2, 4, 8}) {
    p.octaves = octaves;
    auto exact = timed_reference(&sweep.reference_ms, [&] {
      return reference::dilution(images.at("albedo"), normal, &object, p).image;
    });
    for (const char* precision : kPrecisions) {
      configs.push_back(
          {"octaves=" + std::to_string(octaves), {{"octaves", octaves}}, precision, exact});
    }
  }
  auto add_light = [&](Graph& g) {
    Node join;
    join.type = "scene_join";
    join.params["light_direction"] = json::array({light[0], light[1], light[2]});
    g.nodes["input_scene"] = join;
    g.nodes[kNodeUnderTest].inputs["scene"] = PortRef{"input_scene", "scene"};
  };
  if (auto s = run_configs(context, registry, plan, "dilution", params,
                           {{"albedo", "albedo"}, {"normal", "normal"}, {"object", "object"}},
                           images, configs, w, h, &sweep, add_light);
      !s.ok()) {
    return s.error();
  }
  return sweep;
}

}  // namespace

Result<std::vector<Sweep>> run_reference_sweeps(GlContext& context, const Registry& registry,
                                                const Graph& graph, const SweepPlan& plan,
                                                const std::set<std::string>& types) {
  std::vector<Sweep> sweeps;
  auto wanted = [&](const char* type) {
    return types.count(type) > 0 && registry.find(type) != nullptr;
  };
  if (wanted("blur")) {
    auto blur = blur_sweeps(context, registry, graph, plan);
    if (!blur.ok()) return blur.error();
    sweeps.insert(sweeps.end(), blur->begin(), blur->end());
  }
  if (wanted("caustics")) {
    auto caustics = caustics_sweeps(context, registry, graph, plan);
    if (!caustics.ok()) return caustics.error();
    sweeps.insert(sweeps.end(), caustics->begin(), caustics->end());
  }
  for (const char* type : {"erode", "dilate"}) {
    if (!wanted(type)) continue;
    auto morphology = morphology_sweep(context, registry, graph, plan, type);
    if (!morphology.ok()) return morphology.error();
    sweeps.push_back(*morphology);
  }
  if (wanted("tint")) {
    reference::TintParams p;
    p.amount = number(graph_param(graph, registry, "tint", "amount"), p.amount);
    const json tint = vec3_or(graph_param(graph, registry, "tint", "tint"), {0.0, 0.07, 0.1});
    for (int c = 0; c < 3; ++c) p.tint[c] = tint[c].get<double>();
    auto sweep =
        precision_sweep(context, registry, plan, "tint", {{"amount", p.amount}, {"tint", tint}},
                        "reference::tint in double precision",
                        [&](const ImageF& image) { return reference::tint(image, p); });
    if (!sweep.ok()) return sweep.error();
    sweeps.push_back(*sweep);
  }
  if (wanted("edge")) {
    reference::EdgeParams p;
    const json kernel = graph_param(graph, registry, "edge", "kernel");
    p.kernel =
        kernel == "sobel" ? reference::EdgeKernel::kSobel : reference::EdgeKernel::kLaplacian;
    p.factor = number(graph_param(graph, registry, "edge", "factor"), p.factor);
    p.threshold = number(graph_param(graph, registry, "edge", "threshold"), p.threshold);
    p.softness = number(graph_param(graph, registry, "edge", "softness"), p.softness);
    auto sweep = precision_sweep(
        context, registry, plan, "edge",
        {{"kernel", kernel},
         {"factor", p.factor},
         {"threshold", p.threshold},
         {"softness", p.softness}},
        "reference::edge_darkening in double precision (edges of the image itself)",
        [&](const ImageF& image) { return reference::edge_darkening(image, nullptr, p); });
    if (!sweep.ok()) return sweep.error();
    sweeps.push_back(*sweep);
  }
  if (wanted("vignette")) {
    reference::VignetteParams p;
    p.radius = number(graph_param(graph, registry, "vignette", "radius"), p.radius);
    p.strength = number(graph_param(graph, registry, "vignette", "strength"), p.strength);
    p.softness = number(graph_param(graph, registry, "vignette", "softness"), p.softness);
    auto sweep =
        precision_sweep(context, registry, plan, "vignette",
                        {{"radius", p.radius}, {"strength", p.strength}, {"softness", p.softness}},
                        "reference::vignette in double precision",
                        [&](const ImageF& image) { return reference::vignette(image, p); });
    if (!sweep.ok()) return sweep.error();
    sweeps.push_back(*sweep);
  }
  if (wanted("bleed")) {
    auto sweep = bleed_sweep(context, registry, graph, plan);
    if (!sweep.ok()) return sweep.error();
    sweeps.push_back(*sweep);
  }
  if (wanted("edge_darkening")) {
    auto sweep = edge_darkening_sweep(context, registry, graph, plan);
    if (!sweep.ok()) return sweep.error();
    sweeps.push_back(*sweep);
  }
  if (wanted("paper_relief")) {
    auto sweep = paper_relief_sweep(context, registry, plan);
    if (!sweep.ok()) return sweep.error();
    sweeps.push_back(*sweep);
  }
  if (wanted("dilution")) {
    auto sweep = dilution_sweep(context, registry, graph, plan);
    if (!sweep.ok()) return sweep.error();
    sweeps.push_back(*sweep);
  }
  if (wanted("tremor")) {
    reference::TremorParams p;
    p.amplitude = number(graph_param(graph, registry, "tremor", "amplitude"), p.amplitude);
    p.wavelength = number(graph_param(graph, registry, "tremor", "wavelength"), p.wavelength);
    p.speed = 0.0;  // still, so every measured frame has the reference's time
    auto sweep = precision_sweep(
        context, registry, plan, "tremor",
        {{"amplitude", p.amplitude}, {"wavelength", p.wavelength}, {"speed", 0.0}},
        "reference::tremor in double precision (bilinear lookups)",
        [&](const ImageF& image) { return reference::tremor(image, nullptr, 0.0, p); });
    if (!sweep.ok()) return sweep.error();
    sweeps.push_back(*sweep);
  }
  return sweeps;
}

#endif  // AQ_HAVE_CPU_REFERENCES

}  // namespace aq::app
