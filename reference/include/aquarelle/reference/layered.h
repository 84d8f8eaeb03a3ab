// CPU reference of the `layered` node in double precision, written from the maths in
// plugins/layered/README.md (Luft & Deussen's layered watercolor, seeds 003 and 004): the
// per-object table, segmentation and lighting, Gaussian abstraction with a noise-modulated
// threshold, wet edges (3x3 Laplacian, threshold, Gaussian, ease-out), edge darkening,
// granulation, pigment mixing and glazing, the blurred depth test, and soft shadows by the
// blurred depth test as their own translucent layer. The `painting` view.
#pragma once

#include <aquarelle/core/image.h>

#include <array>
#include <map>
#include <vector>

#include "aquarelle/reference/pigment_mix.h"

namespace aq::reference {

struct LayeredParams {
  MixMode mixing = MixMode::kKubelkaMunk;
  std::array<double, 3> light_direction{0.5, -0.7, -0.5};  // travel direction
  std::array<double, 3> view_direction{0.0, 0.0, 1.0};     // towards the viewer
  double shininess = 40.0;
  double specular_threshold = 0.6;
  double light_density = 0.6;
  double dark_density = 1.8;
  std::map<float, Rgb> palette_light;  // id -> light colour (dark: light^(dark/light density))
  double gooch = 0.35;
  Rgb warm{0.95, 0.75, 0.3};
  Rgb cool{0.15, 0.25, 0.6};
  double abstraction_sigma = 3.0;
  double threshold = 0.5;
  double softness = 0.08;
  int wet_edges = 0;  // 0 wet-to-dry, 1 wet-in-wet, 2 none
  std::vector<float> wet_in_wet_ids;
  double edge_threshold = 0.1;
  double edge_width = 2.5;
  double edge_darkness = 0.8;
  double wet_spread = 0.7;
  double edge_darkening = 0.5;
  double edge_noise = 0.08;
  double noise_scale = 24.0;
  double granulation = 0.6;
  Rgb paper_color{0.98, 0.96, 0.9};
  double paper_relief = 0.25;
  double depth_band = 0.3;
  double density = 1.0;
  // Thin shapes: a pixel of the object that is the peak of its blurred mask over a
  // (2r+1)^2 window (r = ceil(sigma) + 1) and at least ~half a pixel wide keeps its coverage.
  double thin_shapes = 1.0;
  // Soft shadows (blurred depth test): glazed after every layer where `shadow` is given.
  double shadows = 0.8;          // pigment of the shadow layer
  double shadow_softness = 4.0;  // Gaussian sigma, pixels
  double shadow_band = 0.05;     // gap behind the occluder (scene units) to full shadow
  Rgb shadow_color{0.35, 0.4, 0.6};
};

struct LayeredObject {
  float id = 0.0f;
  double mean_depth = 0.0;
  Rgb mean_albedo{};
};
// The ids present, far to near (mean positive finite depth descending, then id).
std::vector<LayeredObject> layered_objects(const ImageF& id, const ImageF& depth,
                                           const ImageF& albedo);

// The painting. `paper` (height in channel 0) may be null: flat paper, no granulation.
// `shadow` (may be null: no shadows) holds per pixel the binary visibility from the light in
// channel 0 (1 lit, 0 shadowed) and in channel 1 how far the pixel lies behind its occluder
// along the light (scene units); only object pixels (receivers) read it.
ImageF layered(const ImageF& id, const ImageF& normal, const ImageF& albedo, const ImageF& depth,
               const ImageF* paper, const LayeredParams& params, const ImageF* shadow = nullptr);

}  // namespace aq::reference
