// Object regions and their 8-bit labels: `#include "aquarelle/region_label.glsl"`. cel_light
// paints the regions (its `plain` = regions) and can write each pixel's label into its image's
// alpha (`alpha` = regions); erode and dilate confine their windows to one label, hashing a
// region image's colours or taking the labels from the image's alpha (`labels`). Both ends use
// these two functions, so a label written by the light is the label the morphology would hash.

// A flat colour per object id (0: the background, black), far apart for neighbouring ids.
vec3 aq_region_colour(float id) {
  return fract(id * vec3(0.6180339887, 0.7548776662, 0.5698402910));
}

// The label of a region colour, as a value in alpha (k / 255): a hash of the colour's three
// bytes, so equal colours share a label; two different colours share one with probability 1/256
// (where two such regions touch, they are then filtered as one). reference/morphology.cpp:
// region_label.
float aq_region_label(vec3 colour) {
  uint h = packUnorm4x8(vec4(colour, 0.0));
  h ^= h >> 15;
  h *= 0x2C1B3C6Du;
  h ^= h >> 12;
  h *= 0x297A2D39u;
  h ^= h >> 15;
  return float(h >> 24) * (1.0 / 255.0);
}
