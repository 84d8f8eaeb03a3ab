// erode: morphological erosion (seed §3.3, extended as in §7.4): the minimum over a square or
// disc window of odd size up to 9, per channel or in luminance order. Description and process()
// are shared with `dilate` (aquarelle/sdk/morphology_node.hpp); the shader differs by one define.
#include <aquarelle/sdk/morphology_node.hpp>

#include "erode_shaders.h"

namespace {

struct Erode {
  aq::morphology::Warned warned;
  int process(aq::Context& ctx) {
    return aq::morphology::run(ctx, shaders::erode_frag, aq::morphology::Op::kErode, warned);
  }
};

}  // namespace

AQ_NODE(kErodeNode, Erode, "erode", "Watercolor",
        "Morphological erosion: the minimum over a size x size square or disc window, per "
        "channel or by luminance (output colours are input colours).",
        0, aq::morphology::kInputs, aq::morphology::kOutputs, aq::morphology::kParams);
AQ_PLUGIN("erode", "1.0", &kErodeNode)
