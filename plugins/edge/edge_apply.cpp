// edge_apply: the darkening of `edge` from a weight image of `edge_detect` (seed §3.5): one read
// per pixel instead of the 3×3 detection, as a pointwise node the host fuses into the pass
// before it (in graphs/underwater.json: the wobble's draw, with pigment_apply).
//
//   image ─────────────────────────┐
//   edges (edge_detect: w) ────────┴──► image · mix(1, factor, w) ──► image
#include <aquarelle/plugin.hpp>

#include <string>

#include "edge_shaders.h"
#include "edge_shared.h"

namespace {

constexpr aq_port_desc kInputs[] = {
    aq::image_port("image", "colour to darken"),
    aq::image_port("edges", "the darkening weight of `edge_detect` (r in [0, 1])")};
constexpr aq_port_desc kOutputs[] = {aq::image_port("image", "colour with darkened edges")};
enum Input : uint32_t { kImage, kEdges };
enum Param : uint32_t { kFactor };
constexpr aq_param_desc kParams[] = {edge::kFactorParam};

struct EdgeApply {
  std::string fragment = aq::pointwise_fragment(shaders::edge_apply_glsl.text);

  int process(aq::Context& ctx) {
    const aq_image in = ctx.input_image(kImage);
    if (ctx.param_float(kFactor) >= 1.0) return ctx.pass_through(0, kImage) ? AQ_OK : AQ_ERROR;
    return edge::draw_own_pass(ctx, "edge_apply.glsl", fragment, in, "edges",
                               ctx.input_image(kEdges),
                               [&](GLuint program) { set_uniforms(ctx, program, "u_"); });
  }

  // The uniforms of edge_apply.glsl but the weights, named prefix + name (the host binds the
  // weights when it fuses this node's function).
  int set_uniforms(aq::Context& ctx, GLuint program, const std::string& prefix) {
    aq::set_float(program, (prefix + "factor").c_str(), ctx.param_float(kFactor));
    return AQ_OK;
  }
};

}  // namespace

AQ_POINTWISE_NODE(kEdgeApplyNode, EdgeApply, "edge_apply", "Watercolor",
                  "Darkens edges by the weight of an `edge_detect`: the HSV value times "
                  "mix(1, factor, w); fused into the pass before it.",
                  kInputs, kOutputs, kParams, shaders::edge_apply_glsl, 0);

const aq_node_desc* edge_apply_node_desc() {
  return &kEdgeApplyNode;
}
