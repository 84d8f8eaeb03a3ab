// edge: edge darkening (seed §3.5). Detects edges with the 3×3 Laplacian (−8 centre) or the
// Sobel magnitude and scales the HSV value of edge pixels by `factor` through a smooth
// threshold. With the optional `source` input connected, edges are found on that effect-free
// image and the main image is darkened, the seed's §7.3 fix for caustic and shadow borders.
//
//   image ─────────────┐
//   [source] ──► edges ┴──► image · mix(1, factor, smoothstep(response)) ──► image
#include <aquarelle/plugin.hpp>

#include <string>

#include "edge_shaders.h"
#include "edge_shared.h"

namespace {

constexpr aq_port_desc kInputs[] = {
    aq::image_port("image", "colour to darken"),
    // Detection only thresholds a response of values in [0, 1]: 8 bits are enough, and an
    // 8-bit source halves the cost of the 9 reads per pixel on llvmpipe (plugins/edge/README.md).
    aq_port_desc{"source", AQ_PORT_IMAGE, AQ_PORT_OPTIONAL | AQ_PORT_8BIT_ENOUGH,
                 "effect-free image to detect edges on (seed §7.3), read in 8 bits a channel; "
                 "unconnected: the image itself"}};
constexpr aq_port_desc kOutputs[] = {aq::image_port("image", "colour with darkened edges")};
enum Input : uint32_t { kImage, kSource };
enum Param : uint32_t { kKernel, kFactor, kThreshold, kSoftness };
constexpr aq_param_desc kParams[] = {edge::kKernelParam, edge::kFactorParam, edge::kThresholdParam,
                                     edge::kSoftnessParam};

struct Edge {
  std::string fragment = aq::pointwise_fragment(shaders::edge_glsl.text);

  int process(aq::Context& ctx) {
    const aq_image in = ctx.input_image(kImage);
    if (ctx.param_float(kFactor) >= 1.0) return ctx.pass_through(0, kImage) ? AQ_OK : AQ_ERROR;
    const aq_image source = ctx.connected(kSource) ? ctx.input_image(kSource) : in;
    return edge::draw_own_pass(ctx, "edge.glsl", fragment, in, "source", source,
                               [&](GLuint program) { set_uniforms(ctx, program, "u_"); });
  }

  // The uniforms of edge.glsl but its source, named prefix + name (the host binds the source
  // when it fuses this node's function, which it does only with `source` connected).
  int set_uniforms(aq::Context& ctx, GLuint program, const std::string& prefix) {
    aq::set_float(program, (prefix + "factor").c_str(), ctx.param_float(kFactor));
    edge::set_detection_uniforms(ctx, program, prefix, kKernel, kThreshold, kSoftness);
    return AQ_OK;
  }
};

}  // namespace

const aq_node_desc* edge_detect_node_desc();
const aq_node_desc* edge_apply_node_desc();

AQ_POINTWISE_NODE(kEdgeNode, Edge, "edge", "Watercolor",
                  "Edge darkening: Laplacian or Sobel edges (optionally of an effect-free "
                  "`source`) scale the HSV value by `factor` through a smooth threshold.",
                  kInputs, kOutputs, kParams, shaders::edge_glsl, 1);
AQ_PLUGIN("edge", "1.0", &kEdgeNode, edge_detect_node_desc(), edge_apply_node_desc())
