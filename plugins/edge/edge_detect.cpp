// edge_detect: the darkening weight of `edge` as an image of its own (seed §3.5 and §7.3), for
// `edge_apply`. The weight depends on the source only, so with the output kept between frames
// the node redraws only the pixels whose 3×3 neighbourhood changed: in the flagship the source
// is cel_light's regions (a colour per object id), which change only where the g-buffer does,
// while the caustics move the light, and every pass after it, over most of the frame.
//
//   source ──► 3×3 Laplacian or Sobel ──► w = smoothstep(response) ──► edges (r, 32-bit float)
#include <aquarelle/plugin.hpp>
#include <aquarelle/sdk/region.hpp>

#include "edge_shaders.h"
#include "edge_shared.h"

namespace {

constexpr aq_port_desc kInputs[] = {
    // As `edge`'s source: a thresholded response of values in [0, 1] needs 8 bits at most.
    aq_port_desc{"source", AQ_PORT_IMAGE, AQ_PORT_8BIT_ENOUGH,
                 "image to find edges on (effect-free, seed §7.3), read in 8 bits a channel"}};
constexpr aq_port_desc kOutputs[] = {aq::image_port(
    "edges", "darkening weight w in [0, 1] in r: 0 no edge, 1 a full edge (32-bit float)")};
enum Input : uint32_t { kSource };
enum Param : uint32_t { kKernel, kThreshold, kSoftness };
constexpr aq_param_desc kParams[] = {edge::kKernelParam, edge::kThresholdParam,
                                     edge::kSoftnessParam};

struct EdgeDetect {
  int process(aq::Context& ctx) {
    const aq_image source = ctx.input_image(kSource);
    aq_image out;
    // 32-bit float: edge_apply then darkens exactly as `edge` does in one node.
    if (!ctx.output(0, source.width, source.height, AQ_FORMAT_R32F, &out)) return AQ_ERROR;
    const GLuint program = ctx.program(shaders::edge_detect_frag);
    if (program == 0) return AQ_ERROR;
    glUseProgram(program);
    aq::bind_texture(program, "u_source", 0, source);
    edge::set_detection_uniforms(ctx, program, "u_", kKernel, kThreshold, kSoftness);
    // A kept output is redrawn where a changed source pixel is within the kernel's reach.
    aq::Region damage = aq::Region::everything();
    if (ctx.output_kept(0)) damage = ctx.input_damage(kSource).dilated(1, 1, out.width, out.height);
    if (!ctx.set_draw_region(damage.for_drawing())) damage = aq::Region::everything();
    const bool drawn = ctx.draw(out);
    aq::unbind_textures(1);
    return drawn && ctx.set_output_damage(0, damage) ? AQ_OK : AQ_ERROR;
  }
};

}  // namespace

AQ_NODE(kEdgeDetectNode, EdgeDetect, "edge_detect", "Watercolor",
        "The darkening weight of `edge` on its own: a smooth threshold of the 3×3 Laplacian or "
        "Sobel response of `source`, for edge_apply; redraws only where the source changed.",
        0, kInputs, kOutputs, kParams);

const aq_node_desc* edge_detect_node_desc() {
  return &kEdgeDetectNode;
}
