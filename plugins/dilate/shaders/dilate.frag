// dilate: maximum over the footprint (per channel, or the brightest colour in luminance order).
// The algorithm is shared with `erode` in nodes/shaders/morphology.glsl; only this define
// differs between the two plugins.
#define AQ_MORPH_DILATE 1
#include "aquarelle/morphology.glsl"
