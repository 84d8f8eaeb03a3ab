// An out-of-tree plugin: 1 - rgb. Uses only the installed SDK.
#include <aquarelle/plugin.hpp>

#include "invert_shaders.h"

namespace {
constexpr aq_port_desc kIn[] = {aq::image_port("image", "input")};
constexpr aq_port_desc kOut[] = {aq::image_port("image", "1 - input")};
struct Invert {
  int process(aq::Context& ctx) {
    aq_image in = ctx.input_image(0), out;
    if (!ctx.output_like(0, in, &out)) return AQ_ERROR;
    GLuint program = ctx.program(shaders::invert_frag);
    if (program == 0) return AQ_ERROR;
    glUseProgram(program);
    aq::bind_texture(program, "u_image", 0, in);
    return ctx.draw(out) ? AQ_OK : AQ_ERROR;
  }
};
}  // namespace

AQ_NODE_NO_PARAMS(kInvert, Invert, "sdk_invert", "Test", "1 - rgb", AQ_NODE_POINTWISE, kIn, kOut);
AQ_PLUGIN("sdk_invert", "1.0", &kInvert)
