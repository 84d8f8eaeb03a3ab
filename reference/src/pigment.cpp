// CPU reference of pigment density variation on the dynamic canvas or in object space.
#include "aquarelle/reference/pigment.h"

#include "aquarelle/reference/bilinear.h"
#include "aquarelle/reference/noise_reference.h"

#include <algorithm>
#include <cmath>

namespace aq::reference {
namespace {

constexpr int kTurbulence = 0;
constexpr int kGrain = 1;

double frac(double x) {
  return x - std::floor(x);
}

// GLSL mod: x − y·floor(x / y), non-negative for negative x (std::fmod is not).
double glsl_mod(double x, double y) {
  return x - y * std::floor(x / y);
}

noise::Vec2 field_offset(int source, double layer, int seed) {
  return {glsl_mod(source * 1013.0 + layer * 389.0 + seed * 113.0, 4096.0),
          glsl_mod(source * 577.0 + layer * 211.0 + seed * 71.0, 4096.0)};
}

double procedural2(int source, noise::Vec2 p, int seed) {
  if (source == kTurbulence) return 0.5 * noise::fbm2(p, {0.0, 0.0}, 3);
  if (source == kGrain) {
    return noise::gaussian_noise({std::floor(p.x), std::floor(p.y)}, static_cast<float>(seed)) /
           6.0;
  }
  return 0.5 - std::min(noise::worley2(p, {0.0, 0.0}), 1.0);
}

// The paper's texture is a height: its density is the depth 0.5 - height (pigment settles in
// the valleys), the other textures' their value - 0.5.
double canvas_layer(int source, const ImageF* texture, noise::Vec2 q, double layer, double aspect,
                    const PigmentParams& params) {
  const double sign = source == 2 ? -1.0 : 1.0;
  if (texture != nullptr) {
    const double u = frac(q.x / aspect + 0.5 + layer * 0.6180339887);
    const double v = frac(q.y + 0.5 + layer * 0.3819660113);
    return sign * (sample_bilinear(*texture, u, v, 0) - 0.5);
  }
  const noise::Vec2 offset = field_offset(source, layer, params.seed);
  const double f = params.frequencies[source];
  return sign * procedural2(source, {q.x * f + offset.x, q.y * f + offset.y}, params.seed);
}

double canvas_density(int source, const ImageF* texture, noise::Vec2 screen, double aspect,
                      const PigmentParams& params) {
  const double base = std::floor(params.zoom);
  const double blend = params.zoom - base;
  const noise::Vec2 panned{screen.x + params.pan_x, screen.y + params.pan_y};
  const double s0 = std::exp2(-blend);
  const double n0 =
      canvas_layer(source, texture, {panned.x * s0, panned.y * s0}, base, aspect, params);
  if (blend == 0.0) return n0;
  const double s1 = std::exp2(1.0 - blend);
  const double n1 =
      canvas_layer(source, texture, {panned.x * s1, panned.y * s1}, base + 1.0, aspect, params);
  return ((1.0 - blend) * n0 + blend * n1) / std::hypot(1.0 - blend, blend);
}

double object_density(int source, const double world[3], const PigmentParams& params) {
  const double scale = params.frequencies[source] / params.world_scale;
  const noise::Vec3 p{world[0] * scale, world[1] * scale, world[2] * scale};
  const noise::Vec2 offset = field_offset(source, 0.0, params.seed);
  if (source == kTurbulence) {
    double sum = 0.0;
    double total = 0.0;
    for (int k = 0; k < 3; ++k) {
      const double octave = std::exp2(k);
      const double amplitude = std::exp2(-k);
      sum += amplitude *
             noise::perlin3({p.x * octave + offset.x, p.y * octave + offset.y, p.z * octave},
                            {0.0, 0.0, 0.0});
      total += amplitude;
    }
    return 0.5 * sum / total;
  }
  const double cz = std::floor(p.z);
  return noise::gaussian_noise({std::floor(p.x) + offset.x, std::floor(p.y) + offset.y},
                               static_cast<float>(cz + params.seed * 4099.0)) /
         6.0;
}

}  // namespace

// Above 1 (HDR highlights) only the part up to 1 is modified and the excess kept: the formula
// itself would go negative for c > 1 and d < 1 - 1/(c - 1).
double apply_density(double c, double d) {
  const double low = std::min(c, 1.0);
  return low * (1.0 - (1.0 - low) * (d - 1.0)) + (c - low);
}

ImageF pigment(const ImageF& image, const std::array<const ImageF*, 3>& textures,
               const ImageF* position, const PigmentParams& params) {
  ImageF out = image;
  const double aspect = static_cast<double>(image.width) / image.height;
  for (int y = 0; y < image.height; ++y) {
    for (int x = 0; x < image.width; ++x) {
      const double u = (x + 0.5) / image.width;
      const double v = (y + 0.5) / image.height;
      const noise::Vec2 screen{(u - 0.5) * aspect, v - 0.5};
      bool on_object = false;
      double world[3] = {0, 0, 0};
      if (params.object_anchoring && position != nullptr) {
        const int px = static_cast<int>(u * position->width);
        const int py = static_cast<int>(v * position->height);
        on_object = position->at(px, py, 3) > 0.0f;
        for (int k = 0; k < 3; ++k) world[k] = position->at(px, py, k);
      }
      double rgb[3] = {image.at(x, y, 0), image.at(x, y, 1), image.at(x, y, 2)};
      for (int source = 0; source < 3; ++source) {
        if (params.weights[source] == 0.0) continue;
        const bool from_world = on_object && source != 2 && textures[source] == nullptr;
        double n = from_world ? object_density(source, world, params)
                              : canvas_density(source, textures[source], screen, aspect, params);
        if (!std::isfinite(n)) n = 0.0;
        const double d = std::clamp(1.0 + params.weights[source] * n, 0.0, 2.0);
        for (double& c : rgb) c = apply_density(c, d);
      }
      for (int c = 0; c < 3; ++c) out.at(x, y, c) = static_cast<float>(rgb[c]);
    }
  }
  return out;
}

}  // namespace aq::reference
