// The layered node's inputs and parameters by index, shared by its two methods (layered.cpp,
// fast_layers.cpp); the descriptions are in layered.cpp's kInputs and kParams, in this order.
#pragma once

namespace layered {

enum Input { kId, kNormal, kAlbedo, kDepth, kPaper, kScene, kPosition, kShadow };

enum Param {
  kMixing,
  kView,
  kLightDirection,
  kViewDirection,
  kShininess,
  kSpecularThreshold,
  kLightDensity,
  kDarkDensity,
  kPalette,
  kGooch,
  kWarm,
  kCool,
  kAbstractionSigma,
  kThreshold,
  kSoftness,
  kWetEdges,
  kWetInWetIds,
  kEdgeThreshold,
  kEdgeWidth,
  kEdgeDarkness,
  kWetSpread,
  kEdgeDarkening,
  kEdgeNoise,
  kNoiseScale,
  kGranulation,
  kPaperColor,
  kPaperRelief,
  kDepthBand,
  kDensity,
  kThinShapes,
  kShadows,
  kShadowSoftness,
  kShadowBand,
  kShadowColor,
  kMethod
};
enum WetEdges { kWetToDry = 0, kWetInWet = 1, kNoWetEdges = 2 };
enum Method { kExact = 0, kFast = 1 };

}  // namespace layered
