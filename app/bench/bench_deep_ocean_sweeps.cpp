// The sweeps of `aquarelle bench` for seed 001's deep-ocean parts (issue 38), each timed with
// its error against a reference:
//
//   environment          the panorama's size (1x1 .. 4096x2048) and precision, and a cube
//                        map of six faces and of five, against reference::environment and
//                        environment_cube (the README's view ray and lookups, double precision)
//   caustics shift       the seed's blue shift (and none, and grey) against the converged flux
//                        per texel plus the shift (reference::caustic_flux_by_coverage)
//   caustics blend_interval  five images at successive times, several intervals, against the
//                        weighted mean of the reference's flux at the same five times
//   object terrain_cells the terrain's grid against the 1024-cell grid: g-buffer positions of
//                        the graph's floor seen from above; the time is the mesh's generation
//   light_shafts steps   segments along each view ray against reference::light_shafts at 1024
//                        segments (the integral, converged), on a wall and open water
//   object swim_forward  a model built along each axis, swimming, against the same model built
//                        along +x with swim_forward +x (the parameter must make them equal)
#include <unistd.h>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <memory>
#include <string>

#include "bench_graph_build.h"
#include "bench_reference_configs.h"
#include "bench_sweep.h"

#ifdef AQ_HAVE_CPU_REFERENCES
#include "aquarelle/reference/caustics_flux_reference.h"
#include "aquarelle/reference/environment.h"
#include "aquarelle/reference/light_shafts.h"
#endif

namespace aq::app {

namespace {

using json = nlohmann::json;

// The camera the scene-reading sweeps look through (environment: sideways and a little down;
// terrain and swimming: from above).
const json kSideEye = {0.3, 0.4, 2.5}, kSideTarget = {0.0, 0.3, 0.0};
constexpr double kSideFov = 70.0;

// Adds a scene_join with the given camera (no objects) and feeds its scene to the node under
// test.
std::function<void(Graph&)> with_camera(const json& eye, const json& target, double fov) {
  return [=](Graph& g) {
    Node join;
    join.type = "scene_join";
    join.params["camera_position"] = eye;
    join.params["camera_target"] = target;
    join.params["fov"] = fov;
    join.params["environment"] = "none";
    g.nodes["input_scene"] = join;
    g.nodes[kNodeUnderTest].inputs["scene"] = PortRef{"input_scene", "scene"};
  };
}

// Time of one point from several single-sample measurements.
Spread medians_of(const std::vector<Spread>& runs) {
  std::vector<double> samples;
  for (const Spread& run : runs) samples.push_back(run.median);
  return summarize(samples);
}

#ifdef AQ_HAVE_CPU_REFERENCES

const char* const kPrecisions[] = {"half", "float"};

// A panorama whose colours vary smoothly and step from texel to texel (the bilinear weights
// matter), as the environment test's.
ImageF sweep_panorama(int w, int h) {
  ImageF image(w, h, 4, 1.0f);
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      image.at(x, y, 0) = static_cast<float>(0.5 + 0.5 * std::sin(6.283185307 * x / w));
      image.at(x, y, 1) = static_cast<float>((y + 0.5) / h);
      image.at(x, y, 2) = static_cast<float>(((x * 7 + y * 3) % 11) / 10.0);
    }
  }
  return image;
}

// Object ids: background (0) but for a centred rectangle of id 1, which must be kept.
ImageF sweep_ids(int w, int h) {
  ImageF id(w, h, 4, 0.0f);
  for (int y = h / 3; y < 2 * h / 3; ++y)
    for (int x = w / 3; x < 2 * w / 3; ++x) id.at(x, y, 0) = 1.0f;
  return id;
}

// Cube map face f (0..5): gradients across, a level per face, and texel to texel steps.
ImageF sweep_cube_face(int n, int f) {
  ImageF face(n, n, 4, 1.0f);
  for (int y = 0; y < n; ++y)
    for (int x = 0; x < n; ++x) {
      face.at(x, y, 0) = static_cast<float>(0.2 + 0.6 * (x + 0.5) / n);
      face.at(x, y, 1) = static_cast<float>(0.2 + 0.6 * (y + 0.5) / n);
      face.at(x, y, 2) = static_cast<float>(0.1 * f + ((x * 7 + y * 3) % 11) / 20.0);
    }
  return face;
}

// The environment from six cube faces (256 x 256), and from five (+x missing: looking that way
// shows missing_face_color), against reference::environment_cube.
Status environment_cube_points(GlContext& context, const Registry& registry, const SweepPlan& plan,
                               const reference::EnvironmentParams& p, const ImageF& image,
                               const ImageF& id, Sweep* sweep) {
  const char* const names[6] = {"cube_px", "cube_nx", "cube_py", "cube_ny", "cube_pz", "cube_nz"};
  std::map<std::string, ImageF> images{{"image", image}, {"id", id}};
  for (int f = 0; f < 6; ++f) images[names[f]] = sweep_cube_face(256, f);
  for (int first : {0, 1}) {  // all six faces; then without +x
    const ImageF* faces[6];
    std::map<std::string, std::string> inputs{{"image", "image"}, {"id", "id"}};
    for (int f = 0; f < 6; ++f) {
      faces[f] = f >= first ? &images.at(names[f]) : nullptr;
      if (f >= first) inputs[names[f]] = names[f];
    }
    auto exact = timed_reference(&sweep->reference_ms, [&] {
      return reference::environment_cube(image, id, faces, {0.0, 0.0, 0.0}, p);
    });
    const std::string setting = first == 0 ? "cube 6 x 256x256" : "cube, +x missing";
    std::vector<ReferenceConfig> configs;
    for (const char* precision : kPrecisions) configs.push_back({setting, {}, precision, exact});
    if (auto s = run_configs(context, registry, plan, "environment", {{"intensity", p.intensity}},
                             inputs, images, configs, plan.width, plan.height, sweep,
                             with_camera(kSideEye, kSideTarget, kSideFov));
        !s.ok()) {
      return s;
    }
  }
  return Ok{};
}

Result<Sweep> environment_sweep(GlContext& context, const Registry& registry, const Graph& graph,
                                const SweepPlan& plan) {
  const int w = plan.width, h = plan.height;
  reference::EnvironmentParams p;
  for (int k = 0; k < 3; ++k) {
    p.eye[k] = kSideEye[k].get<double>();
    p.target[k] = kSideTarget[k].get<double>();
  }
  p.fov_degrees = kSideFov;
  p.rotation_degrees = number(graph_param(graph, registry, "environment", "rotation"), 0.0);
  p.intensity = number(graph_param(graph, registry, "environment", "intensity"), 1.0);
  Sweep sweep = cpu_sweep("environment", "environment",
                          "reference::environment in double precision (the README's view ray, "
                          "longitude and latitude, bilinear panorama lookup wrapping in "
                          "longitude), on a panorama of each size");
  sweep.note =
      "the node has no quality setting: the cost is one pass whatever the panorama's size "
      "(upload not counted); the error is llvmpipe's atan/asin against double precision, in "
      "panorama texels, so it grows with the panorama's size";
  const ImageF image = sweep_test_image(w, h), id = sweep_ids(w, h);
  const int sizes[][2] = {{1, 1}, {64, 32}, {512, 256}, {4096, 2048}};
  for (const auto& size : sizes) {
    std::map<std::string, ImageF> images{{"image", image}, {"id", id}};
    images["panorama"] = sweep_panorama(size[0], size[1]);
    auto exact = timed_reference(&sweep.reference_ms, [&] {
      return reference::environment(image, id, images.at("panorama"), p);
    });
    const std::string setting =
        "panorama " + std::to_string(size[0]) + "x" + std::to_string(size[1]);
    std::vector<ReferenceConfig> configs;
    for (const char* precision : kPrecisions) configs.push_back({setting, {}, precision, exact});
    if (auto s = run_configs(context, registry, plan, "environment",
                             {{"rotation", p.rotation_degrees}, {"intensity", p.intensity}},
                             {{"image", "image"}, {"id", "id"}, {"panorama", "panorama"}}, images,
                             configs, w, h, &sweep, with_camera(kSideEye, kSideTarget, kSideFov));
        !s.ok()) {
      return s.error();
    }
  }
  if (auto s = environment_cube_points(context, registry, plan, p, image, id, &sweep); !s.ok())
    return s.error();
  return sweep;
}

// The caustic texture of the sweeps: 64 texels, the node on a 128 grid (coverage), the
// reference on a 512 grid (8 cells per texel).
constexpr int kCausticResolution = 64, kCausticGrid = 128, kCausticReferenceGrid = 512;

// The blended reference: Σ w_k E(t − k·interval) / Σ w_k + shift, the flux of each time
// computed once (`cache`, by time).
ImageF blended_flux(reference::CausticsParams p, int count, double interval, const double shift[3],
                    std::map<double, std::vector<double>>* cache) {
  const double weights[5] = {0.4, 0.3, 0.2, 0.1, 0.05};
  const int n = p.resolution;
  std::vector<double> sum(static_cast<size_t>(n) * n, 0.0);
  double total = 0.0;
  for (int k = 0; k < count; ++k) {
    const double time = -k * interval;  // the graph's first frame is time 0
    auto found = cache->find(time);
    if (found == cache->end()) {
      p.time = time;
      found =
          cache->emplace(time, reference::caustic_flux_by_coverage(p, kCausticReferenceGrid)).first;
    }
    for (size_t i = 0; i < sum.size(); ++i) sum[i] += weights[k] * found->second[i];
    total += weights[k];
  }
  for (double& v : sum) v /= total;
  ImageF image = reference::to_caustic_image(sum, n);
  for (int y = 0; y < n; ++y)
    for (int x = 0; x < n; ++x)
      for (int c = 0; c < 3; ++c) image.at(x, y, c) += static_cast<float>(shift[c]);
  return image;
}

Result<std::vector<Sweep>> caustics_seed_sweeps(GlContext& context, const Registry& registry,
                                                const Graph& graph, const SweepPlan& plan) {
  const reference::CausticsParams p = caustics_params_of(graph, registry, kCausticResolution);
  const json base = {{"resolution", p.resolution},
                     {"grid", kCausticGrid},
                     {"estimator", "coverage"},
                     {"depth", p.depth},
                     {"amplitude", p.amplitude},
                     {"wave_scale", p.wave_scale},
                     {"speed", p.speed},
                     {"eta", p.eta},
                     {"max_intensity", p.max_intensity}};
  const std::string precision = graph.settings.precision;
  char text[256];
  std::snprintf(text, sizeof(text),
                "exact box-filtered flux per texel (reference::caustic_flux_by_coverage) on a "
                "%dx%d grid in double precision, texture %dx%d; the node on grid %d",
                kCausticReferenceGrid, kCausticReferenceGrid, p.resolution, p.resolution,
                kCausticGrid);
  std::map<double, std::vector<double>> cache;
  std::vector<Sweep> sweeps;

  Sweep shift =
      cpu_sweep("caustics shift", "caustics", std::string(text) + ", plus the shift per channel");
  shift.note =
      "a shift other than 0 costs one more pass (the blend pass adds it; with none and one "
      "image the estimator writes the output directly)";
  const double shifts[][3] = {{0.0, 0.0, 0.0}, {0.0, 0.05, 0.1}, {0.1, 0.1, 0.1}};
  std::vector<ReferenceConfig> configs;
  for (const auto& s : shifts) {
    auto exact =
        timed_reference(&shift.reference_ms, [&] { return blended_flux(p, 1, 0.0, s, &cache); });
    char setting[64];
    std::snprintf(setting, sizeof(setting), "shift=(%g, %g, %g)", s[0], s[1], s[2]);
    configs.push_back({setting, {{"shift", {s[0], s[1], s[2]}}}, precision, exact});
  }
  if (auto s = run_configs(context, registry, plan, "caustics", base, {}, {}, configs, plan.width,
                           plan.height, &shift);
      !s.ok()) {
    return s.error();
  }
  sweeps.push_back(shift);

  Sweep interval = cpu_sweep("caustics blend_interval", "caustics",
                             std::string(text) + ", five times mixed with the seed's weights");
  interval.note =
      "blend_count 5: each point renders the estimator five times (the interval changes what "
      "is blended, not the cost); interval 0 blends five copies of one time";
  configs.clear();
  const double none[3] = {0.0, 0.0, 0.0};
  for (double seconds : {0.0, 0.05, 0.2, 0.5, 1.0}) {
    auto exact = timed_reference(&interval.reference_ms,
                                 [&] { return blended_flux(p, 5, seconds, none, &cache); });
    char setting[64];
    std::snprintf(setting, sizeof(setting), "blend_interval=%g", seconds);
    configs.push_back(
        {setting, {{"blend_count", 5}, {"blend_interval", seconds}}, precision, exact});
  }
  if (auto s = run_configs(context, registry, plan, "caustics", base, {}, {}, configs, plan.width,
                           plan.height, &interval);
      !s.ok()) {
    return s.error();
  }
  sweeps.push_back(interval);
  return sweeps;
}

// A caustic texture with sharp bright lines (0.4 .. 3.5) on a 32 x 32 tile, for light_shafts.
ImageF sweep_caustic_lines() {
  ImageF c(32, 32, 4, 1.0f);
  for (int y = 0; y < 32; ++y)
    for (int x = 0; x < 32; ++x) {
      const double v = 0.4 + 3.1 * std::pow(std::abs(std::sin(0.45 * x + 0.15 * y)), 8.0);
      for (int k = 0; k < 3; ++k) c.at(x, y, k) = static_cast<float>(v);
    }
  return c;
}

// World positions of a wall the light grazes (x = -1, facing +x) over the left two thirds,
// seen by the sweep's side camera; open water (alpha 0) on the right.
ImageF sweep_wall(int w, int h) {
  ImageF p(w, h, 4, 0.0f);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < 2 * w / 3; ++x) {
      p.at(x, y, 0) = -1.0f;
      p.at(x, y, 1) = static_cast<float>(-2.0 + 6.0 * y / h);
      p.at(x, y, 2) = static_cast<float>(-8.0 + 7.0 * x / w);
      p.at(x, y, 3) = 1.0f;
    }
  return p;
}

Result<Sweep> light_shafts_sweep(GlContext& context, const Registry& registry, const Graph& graph,
                                 const SweepPlan& plan) {
  const int w = plan.width, h = plan.height;
  reference::LightShaftsParams p;
  for (int k = 0; k < 3; ++k) {
    p.eye[k] = kSideEye[k].get<double>();
    p.target[k] = kSideTarget[k].get<double>();
  }
  p.fov_degrees = kSideFov;
  p.light_direction = {0.28, -0.96, 0.0};
  p.light_color = {1.0, 1.0, 1.0};
  p.water_height = 6.0;
  p.tile = 2.0;
  p.strength = number(graph_param(graph, registry, "light_shafts", "strength"), p.strength);
  p.extinction = number(graph_param(graph, registry, "light_shafts", "extinction"), p.extinction);
  p.max_distance =
      number(graph_param(graph, registry, "light_shafts", "max_distance"), p.max_distance);
  const std::map<std::string, ImageF> images{{"image", sweep_test_image(w, h)},
                                             {"position", sweep_wall(w, h)},
                                             {"caustics", sweep_caustic_lines()}};
  Sweep sweep = cpu_sweep("light_shafts steps", "light_shafts",
                          "reference::light_shafts in double precision at 1024 segments (the "
                          "integral along each ray, converged)");
  reference::LightShaftsParams converged = p;
  converged.steps = 1024;
  auto exact = timed_reference(&sweep.reference_ms, [&] {
    return reference::light_shafts(images.at("image"), images.at("position"), images.at("caustics"),
                                   converged);
  });
  converged.steps = 512;
  const ImageF half = reference::light_shafts(images.at("image"), images.at("position"),
                                              images.at("caustics"), converged);
  double largest = 0.0;
  for (size_t i = 0; i < half.pixels.size(); ++i)
    largest = std::max<double>(largest, std::abs(half.pixels[i] - exact->pixels[i]));
  char note[200];
  std::snprintf(note, sizeof(note),
                "reference's own error: 512 and 1024 segments differ by at most %.1e; a wall "
                "the light grazes (left) and open water to max_distance %g (right)",
                largest, p.max_distance);
  sweep.note = note;
  std::vector<ReferenceConfig> configs;
  for (int steps : {4, 8, 16, 32, 64}) {
    for (const char* precision : kPrecisions) {
      configs.push_back({"steps=" + std::to_string(steps), {{"steps", steps}}, precision, exact});
    }
  }
  const json params = {{"strength", p.strength},
                       {"extinction", p.extinction},
                       {"max_distance", p.max_distance},
                       {"caustic_tile", p.tile}};
  auto add_scene = [&](Graph& g) {
    Node join;
    join.type = "scene_join";
    join.params["camera_position"] = kSideEye;
    join.params["camera_target"] = kSideTarget;
    join.params["fov"] = kSideFov;
    join.params["light_direction"] = json::array({0.28, -0.96, 0.0});
    join.params["light_color"] = json::array({1.0, 1.0, 1.0});
    join.params["light_intensity"] = 1.0;
    join.params["water_height"] = p.water_height;
    join.params["environment"] = "none";
    g.nodes["input_scene"] = join;
    g.nodes[kNodeUnderTest].inputs["scene"] = PortRef{"input_scene", "scene"};
  };
  if (auto s = run_configs(context, registry, plan, "light_shafts", params,
                           {{"image", "image"}, {"position", "position"}, {"caustics", "caustics"}},
                           images, configs, w, h, &sweep, add_scene);
      !s.ok()) {
    return s.error();
  }
  return sweep;
}

#endif  // AQ_HAVE_CPU_REFERENCES

// The graph's first `object` whose source is `terrain`; empty when none.
std::string terrain_node(const Graph& graph) {
  for (const auto& [id, node] : graph.nodes) {
    auto source = node.params.find("source");
    if (node.type == "object" && source != node.params.end() && source->second == "terrain")
      return id;
  }
  return "";
}

// The floor alone (the graph's terrain parameters, the unit square at the origin) seen from
// above through a g-buffer: its world positions.
Graph terrain_graph(const Graph& graph, const std::string& floor_id, int cells,
                    const SweepPlan& plan, const std::string& precision) {
  Graph g;
  g.settings.width = plan.width;
  g.settings.height = plan.height;
  g.settings.precision = precision;
  Node floor;
  floor.type = "object";
  for (const auto& [name, value] : graph.nodes.at(floor_id).params) {
    if (name.rfind("terrain_", 0) == 0 || name == "seed" || name == "source")
      floor.params[name] = value;
  }
  floor.params["terrain_cells"] = cells;
  g.nodes["floor"] = floor;
  Node join;
  join.type = "scene_join";
  // Narrow enough that the floor fills the frame at 16:9: no pixel at its edge, where a point
  // on or off the floor would count as a height error.
  join.params["camera_position"] = json::array({0.0, 1.6, 0.9});
  join.params["camera_target"] = json::array({0.0, 0.0, 0.0});
  join.params["fov"] = 15.0;
  join.params["environment"] = "none";
  join.inputs["objects"] = PortRef{"floor", "object"};
  g.nodes["join"] = join;
  Node gbuffer;
  gbuffer.type = "gbuffer";
  gbuffer.inputs["scene"] = PortRef{"join", "scene"};
  g.nodes["gbuf"] = gbuffer;
  g.output = PortRef{"gbuf", "position"};
  return g;
}

// The terrain's grid: the object node's time on a fresh evaluator (the mesh is generated on
// its first evaluation, then kept), and the floor's positions against the 1024-cell grid.
Result<Sweep> terrain_sweep(GlContext& context, const Registry& registry, const Graph& graph,
                            const SweepPlan& plan, const std::string& floor_id) {
  constexpr int kReferenceCells = 1024;
  Sweep sweep;
  sweep.series = "object terrain_cells";
  sweep.node_type = "object";
  sweep.kind = "highest_quality";
  sweep.reference = "g-buffer world positions of '" + floor_id +
                    "''s terrain (unit square, seen from above) with terrain_cells = 1024, float";
  sweep.time_measure = "node wall (mesh generation: first evaluation)";
  sweep.note =
      "the grid is linear between vertices (second order): the 1024 grid's own error is about "
      "a third of the 512 grid's against it; positions in object units (the floor is 1 wide)";
  ImageF reference;
  {
    Evaluator evaluator(context, registry);
    auto measured =
        measure_node(evaluator, terrain_graph(graph, floor_id, kReferenceCells, plan, "float"),
                     "floor", nullptr, 1, 0);
    if (!measured.ok()) return make_error("terrain sweep: " + measured.message());
    reference = std::move(measured->output);
  }
  for (int cells : {16, 32, 64, 128, 256, 512, kReferenceCells}) {
    const std::string precision = cells == kReferenceCells ? "float" : graph.settings.precision;
    const Graph g = terrain_graph(graph, floor_id, cells, plan, precision);
    std::vector<Spread> runs;
    ImageF output;
    for (int run = 0; run < std::max(plan.frames, 1); ++run) {
      Evaluator evaluator(context, registry);  // a new node: the mesh is generated again
      auto measured = measure_node(evaluator, g, "floor", nullptr, 1, 0);
      if (!measured.ok()) return make_error("terrain sweep: " + measured.message());
      runs.push_back(measured->wall_ms);
      output = std::move(measured->output);
    }
    auto error = compare_images(output, reference);
    if (!error.ok()) return make_error("terrain sweep: " + error.message());
    SweepPoint point;
    point.setting = "terrain_cells=" + std::to_string(cells);
    point.params = {{"terrain_cells", cells}};
    point.precision = precision;
    point.time_ms = medians_of(runs);
    point.error = *error;
    point.is_reference = cells == kReferenceCells;
    sweep.points.push_back(point);
  }
  return sweep;
}

// A fish-like body 1 long along +x (nose at +0.5, a narrow tail at -0.5), its vertices turned
// so that the nose points along `forward` (+x, -x, +z, -z): exact coordinate swaps, so every
// file holds the same body.
std::string swim_body(const std::string& forward) {
  std::string text = "# swim_forward sweep body (aquarelle bench)\n";
  const int rings = 12, sides = 8;
  char line[128];
  for (int i = 0; i <= rings; ++i) {
    const double x = -0.5 + double(i) / rings;
    const double r = 0.02 + 0.1 * std::sin(3.14159265358979 * (x + 0.5) * 0.8 + 0.3);
    for (int j = 0; j < sides; ++j) {
      const double a = 6.283185307179586 * j / sides;
      const double y = r * std::cos(a), z = 0.6 * r * std::sin(a);
      double out[3] = {x, y, z};
      if (forward == "-x") out[0] = -x, out[2] = -z;
      if (forward == "+z") out[0] = -z, out[2] = x;
      if (forward == "-z") out[0] = z, out[2] = -x;
      std::snprintf(line, sizeof(line), "v %.9g %.9g %.9g\n", out[0], out[1], out[2]);
      text += line;
    }
  }
  for (int i = 0; i < rings; ++i) {
    for (int j = 0; j < sides; ++j) {
      const int a = i * sides + j + 1, b = i * sides + (j + 1) % sides + 1;
      std::snprintf(line, sizeof(line), "f %d %d %d\nf %d %d %d\n", a, b, b + sides, a, b + sides,
                    a + sides);
      text += line;
    }
  }
  return text;
}

// True when an `object` of the graph swims (the swim_forward sweep is about those).
bool has_swimmer(const Graph& graph) {
  for (const auto& [id, node] : graph.nodes) {
    auto animation = node.params.find("animation");
    if (node.type == "object" && animation != node.params.end() && animation->second == "swim")
      return true;
  }
  return false;
}

// The swimming body along `forward` with swim_forward = `forward`, seen from above: positions.
Graph swim_graph(const std::string& path, const std::string& forward, double wave,
                 const SweepPlan& plan, const std::string& precision) {
  Graph g;
  g.settings.width = plan.width;
  g.settings.height = plan.height;
  g.settings.precision = precision;
  g.settings.first_frame = 1;
  Node body;
  body.type = "object";
  body.params = {{"path", path},      {"animation", "swim"}, {"swim_forward", forward},
                 {"swim_wave", wave}, {"swim_radius", 0.5},  {"swim_speed", 1.0},
                 {"swim_phase", 30.0}};
  g.nodes["body"] = body;
  Node join;
  join.type = "scene_join";
  join.params["camera_position"] = json::array({0.0, 2.0, 0.01});
  join.params["camera_target"] = json::array({0.0, 0.0, 0.0});
  join.params["fov"] = 45.0;
  join.params["environment"] = "none";
  join.inputs["objects"] = PortRef{"body", "object"};
  g.nodes["join"] = join;
  Node gbuffer;
  gbuffer.type = "gbuffer";
  gbuffer.inputs["scene"] = PortRef{"join", "scene"};
  g.nodes["gbuf"] = gbuffer;
  g.output = PortRef{"gbuf", "position"};
  return g;
}

Result<Sweep> swim_forward_sweep(GlContext& context, const Registry& registry, const Graph& graph,
                                 const SweepPlan& plan) {
  namespace fs = std::filesystem;
  double wave = 0.056;
  for (const auto& [id, node] : graph.nodes) {
    auto animation = node.params.find("animation");
    auto amplitude = node.params.find("swim_wave");
    if (node.type == "object" && animation != node.params.end() && animation->second == "swim" &&
        amplitude != node.params.end() && number(amplitude->second, 0.0) > 0.0) {
      wave = amplitude->second.get<double>();
      break;
    }
  }
  Sweep sweep;
  sweep.series = "object swim_forward";
  sweep.node_type = "object";
  sweep.kind = "equivalence_reference";
  sweep.reference =
      "g-buffer positions of the same body built along +x, swim_forward +x, float: a body built "
      "along another axis with that swim_forward must swim exactly so";
  sweep.time_measure = "node wall (body wave every frame)";
  char note[160];
  std::snprintf(note, sizeof(note),
                "swim_wave %g (the graph's first swimming object's, else the default); the body "
                "is 1 long, seen from above at frame 1",
                wave);
  sweep.note = note;
  const fs::path dir =
      fs::temp_directory_path() / ("aquarelle_bench_swim_" + std::to_string(getpid()));
  std::error_code ec;
  fs::create_directories(dir, ec);
  if (ec)
    return make_error("swim_forward sweep: cannot make " + dir.string() + ": " + ec.message());
  auto body_path = [&](const std::string& forward) {
    const fs::path path =
        dir / ("body" + std::string(forward[0] == '+' ? "p" : "n") + forward.substr(1) + ".obj");
    std::ofstream(path) << swim_body(forward);
    return path.string();
  };
  Evaluator evaluator(context, registry);
  auto reference = measure_node(evaluator, swim_graph(body_path("+x"), "+x", wave, plan, "float"),
                                "body", nullptr, 0, plan.warmup);
  Result<Sweep> result = sweep;
  if (!reference.ok()) {
    result = make_error("swim_forward sweep: " + reference.message());
  } else {
    for (const char* forward : {"+x", "-x", "+z", "-z"}) {
      Evaluator fresh(context, registry);
      auto measured = measure_node(
          fresh, swim_graph(body_path(forward), forward, wave, plan, graph.settings.precision),
          "body", nullptr, plan.frames, plan.warmup);
      if (!measured.ok()) {
        result = make_error("swim_forward sweep: " + measured.message());
        break;
      }
      auto error = compare_images(measured->output, reference->output);
      if (!error.ok()) {
        result = make_error("swim_forward sweep: " + error.message());
        break;
      }
      SweepPoint point;
      point.setting = std::string("swim_forward=") + forward;
      point.params = {{"swim_forward", forward}};
      point.precision = graph.settings.precision;
      point.time_ms = measured->wall_ms;
      point.gpu_ms = measured->gpu_ms;
      point.error = *error;
      result->points.push_back(point);
    }
  }
  fs::remove_all(dir, ec);
  return result;
}

}  // namespace

Result<std::vector<Sweep>> run_deep_ocean_sweeps(GlContext& context, const Registry& registry,
                                                 const Graph& graph, const SweepPlan& plan,
                                                 const std::set<std::string>& types) {
  std::vector<Sweep> sweeps;
  auto wanted = [&](const char* type) {
    return types.count(type) > 0 && registry.find(type) != nullptr;
  };
#ifdef AQ_HAVE_CPU_REFERENCES
  if (wanted("environment")) {
    auto sweep = environment_sweep(context, registry, graph, plan);
    if (!sweep.ok()) return sweep.error();
    sweeps.push_back(*sweep);
  }
  if (wanted("light_shafts")) {
    auto sweep = light_shafts_sweep(context, registry, graph, plan);
    if (!sweep.ok()) return sweep.error();
    sweeps.push_back(*sweep);
  }
  if (wanted("caustics")) {
    auto seed = caustics_seed_sweeps(context, registry, graph, plan);
    if (!seed.ok()) return seed.error();
    sweeps.insert(sweeps.end(), seed->begin(), seed->end());
  }
#endif
  if (wanted("object")) {
    if (const std::string floor = terrain_node(graph); !floor.empty()) {
      auto sweep = terrain_sweep(context, registry, graph, plan, floor);
      if (!sweep.ok()) return sweep.error();
      sweeps.push_back(*sweep);
    }
    if (has_swimmer(graph)) {
      auto sweep = swim_forward_sweep(context, registry, graph, plan);
      if (!sweep.ok()) return sweep.error();
      sweeps.push_back(*sweep);
    }
  }
  return sweeps;
}

}  // namespace aq::app
