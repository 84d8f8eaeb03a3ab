// CPU reference of the `dilution` node in double precision (plugins/dilution/README.md):
// lit = clamp((N·L + a − 1)/a, 0, 1), C_c = albedo + clamp(cangiante · lit, 0, 1) (Montesdeoca
// et al. 2017, eq. "cangiante"), τ = turbulence · fbm3(anchor · scale),
// dil = clamp(dilution · lit · (1 + τ), 0, 1), out = mix(C_c, paper, dil) · (1 − shade (1 − lit)).
#pragma once

#include <aquarelle/core/image.h>

#include <array>

namespace aq::reference {

struct DilutionParams {
  double dilution = 0.8;
  double diffuse_area = 1.0;
  double shade = 0.25;
  double cangiante = 0.2;
  double turbulence = 0.5;  // used only with an anchor image
  double scale = 3.0;
  int octaves = 4;
  double turbulence_bend = 0.0;  // > 0: noise::fbm3_bent (seed 002's cubism)
  std::array<double, 3> paper{0.96, 0.93, 0.85};
  std::array<double, 3> to_light{0.0, 1.0, 0.0};  // unit
};

struct DilutionResult {
  ImageF image;
  ImageF dilution;
};

DilutionResult dilution(const ImageF& albedo, const ImageF& normal, const ImageF* anchor,
                        const DilutionParams& params = {});

}  // namespace aq::reference
