// The normal smoothing sweep of `aquarelle bench`: the scene node's load-time smoothing
// (mesh_smoothing.hpp, Paré-Vogt & Chaid §3.2) at several iteration counts, timed on the CPU and
// compared with the normals of the smooth shape a low-poly mesh stands for.
//
// What smoothing is for: the seed's models are faceted and bumpy, and cel bands should follow
// their overall shape, not every facet. The test mesh makes that shape known: a UV sphere with
// its vertices pushed in and out by up to 5 % (a rock), drawn flat-shaded (three vertices per
// triangle, each with its face normal) as the scene's shapes are. The reference at a vertex is
// the unit sphere's normal, the direction of its position. Zero iterations keep the facets;
// each iteration averages over one more ring of neighbours.
#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <string>
#include <vector>

#include <aquarelle/sdk/mesh_smoothing.hpp>

#include "bench_sweep.h"

namespace aq::app {

namespace {

struct TestMesh {
  std::vector<float> positions;
  std::vector<uint32_t> indices;
  std::vector<float> normals;  // flat: each triangle's face normal at its three vertices
};

// A deterministic value in [-1, 1] for a grid point (splitmix64).
double jitter(int ring, int segment) {
  uint64_t z = (static_cast<uint64_t>(ring) << 32) ^ static_cast<uint64_t>(segment);
  z += 0x9E3779B97F4A7C15ull;
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
  z ^= z >> 31;
  return static_cast<double>(z >> 11) / static_cast<double>(1ull << 52) - 1.0;
}

TestMesh bumpy_sphere(int rings, int segments, double bump) {
  const double pi = std::acos(-1.0);
  auto point = [&](int ring, int segment) {
    segment %= segments;  // the seam shares its positions
    const double theta = pi * ring / rings;
    const double phi = 2.0 * pi * segment / segments;
    // The poles are one point each, whatever the segment.
    const double r = 1.0 + bump * jitter(ring, ring == 0 || ring == rings ? 0 : segment);
    return std::array<double, 3>{r * std::sin(theta) * std::cos(phi), r * std::cos(theta),
                                 r * std::sin(theta) * std::sin(phi)};
  };
  TestMesh mesh;
  auto triangle = [&](std::array<double, 3> a, std::array<double, 3> b, std::array<double, 3> c) {
    const double u[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]};
    const double v[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
    double n[3] = {u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]};
    const double length = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    if (!(length > 1e-12)) return;  // a sliver at a pole
    for (const auto& p : {a, b, c}) {
      mesh.indices.push_back(static_cast<uint32_t>(mesh.positions.size() / 3));
      for (int k = 0; k < 3; ++k) {
        mesh.positions.push_back(static_cast<float>(p[k]));
        mesh.normals.push_back(static_cast<float>(n[k] / length));
      }
    }
  };
  for (int ring = 0; ring < rings; ++ring) {
    for (int segment = 0; segment < segments; ++segment) {
      // Counter-clockwise seen from outside.
      triangle(point(ring, segment), point(ring + 1, segment + 1), point(ring + 1, segment));
      triangle(point(ring, segment), point(ring, segment + 1), point(ring + 1, segment + 1));
    }
  }
  return mesh;
}

// Normals as a one-row image (rgb = xyz), so they compare like every other sweep's output.
ImageF as_image(const std::vector<float>& normals) {
  ImageF image(static_cast<int>(normals.size() / 3), 1, 3);
  image.pixels = normals;
  return image;
}

double mean_angle_degrees(const std::vector<float>& got, const std::vector<float>& want) {
  double sum = 0.0;
  const size_t n = got.size() / 3;
  for (size_t i = 0; i < n; ++i) {
    double dot = 0.0;
    for (int k = 0; k < 3; ++k) dot += double(got[3 * i + k]) * want[3 * i + k];
    sum += std::acos(std::clamp(dot, -1.0, 1.0));
  }
  return n > 0 ? sum / static_cast<double>(n) * 180.0 / std::acos(-1.0) : 0.0;
}

}  // namespace

Result<Sweep> smoothing_sweep(const SweepPlan& plan, int graph_iterations) {
  constexpr int kRings = 10, kSegments = 16;
  constexpr double kBump = 0.05;
  const TestMesh mesh = bumpy_sphere(kRings, kSegments, kBump);
  std::vector<float> reference(mesh.positions.size());
  for (size_t i = 0; i < mesh.positions.size(); i += 3) {
    const double x = mesh.positions[i], y = mesh.positions[i + 1], z = mesh.positions[i + 2];
    const double length = std::sqrt(x * x + y * y + z * z);
    for (int k = 0; k < 3; ++k)
      reference[i + k] = static_cast<float>(mesh.positions[i + k] / length);
  }
  const ImageF reference_image = as_image(reference);

  Sweep sweep;
  sweep.series = "scene smoothing";
  sweep.node_type = "scene";
  sweep.kind = "analytic_reference";
  sweep.reference = "normals of the unit sphere that a flat-shaded " + std::to_string(kRings) +
                    "x" + std::to_string(kSegments) + " UV sphere with 5 % radial bumps stands for";
  sweep.time_measure = "CPU wall, once per geometry";
  std::string angles;
  std::vector<int> counts = {0, 1, 2, 4, 7, 15, 31, 64};
  if (std::find(counts.begin(), counts.end(), graph_iterations) == counts.end() &&
      graph_iterations >= 0) {
    counts.push_back(graph_iterations);
    std::sort(counts.begin(), counts.end());
  }
  for (int iterations : counts) {
    std::vector<double> samples;
    std::vector<float> normals;
    for (int i = 0; i < plan.warmup + std::max(plan.frames, 1); ++i) {
      normals = mesh.normals;
      aq::mesh::SmoothingOptions options;
      options.iterations = iterations;
      const auto start = std::chrono::steady_clock::now();
      aq::mesh::smooth_normals(mesh.positions, mesh.indices, normals, options);
      const double ms =
          std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start)
              .count();
      if (i >= plan.warmup) samples.push_back(ms);
    }
    auto error = compare_images(as_image(normals), reference_image);
    if (!error.ok()) return make_error("smoothing sweep: " + error.message());
    SweepPoint point;
    point.setting = "smoothing=" + std::to_string(iterations);
    point.params = {{"smoothing", iterations}};
    point.precision = "float";
    point.time_ms = summarize(samples);
    point.error = *error;
    sweep.points.push_back(point);
    char angle[64];
    std::snprintf(angle, sizeof(angle), "%s%d: %.1f°", angles.empty() ? "" : ", ", iterations,
                  mean_angle_degrees(normals, reference));
    angles += angle;
  }
  // Sentence case, no final full stop: reports append their own.
  sweep.note = "Mean angle to the sphere's normal by iterations: " + angles + "; the graph uses " +
               std::to_string(graph_iterations);
  return sweep;
}

}  // namespace aq::app
