// dilate: morphological dilation (seed §3.3, extended as in §7.4): the maximum over a square or
// disc window of odd size up to 9, per channel or in luminance order. Description and process()
// are shared with `erode` (aquarelle/sdk/morphology_node.hpp); the shader differs by one define.
#include <aquarelle/sdk/morphology_node.hpp>

#include "dilate_shaders.h"

namespace {

struct Dilate {
  aq::morphology::Warned warned;
  int process(aq::Context& ctx) {
    return aq::morphology::run(ctx, shaders::dilate_frag, aq::morphology::Op::kDilate, warned);
  }
};

}  // namespace

AQ_NODE(kDilateNode, Dilate, "dilate", "Watercolor",
        "Morphological dilation: the maximum over a size x size square or disc window, per "
        "channel or by luminance (output colours are input colours).",
        0, aq::morphology::kInputs, aq::morphology::kOutputs, aq::morphology::kParams);
AQ_PLUGIN("dilate", "1.0", &kDilateNode)
