// erode: minimum over the footprint (per channel, or the darkest colour in luminance order).
// The algorithm is shared with `dilate` in nodes/shaders/morphology.glsl; only this define
// differs between the two plugins.
#include "aquarelle/morphology.glsl"
