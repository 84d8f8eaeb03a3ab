// dilution: the watercolor reflectance of MNPR (Montesdeoca et al. 2017) as seed 002 uses it.
// Light does not brighten the paint, it dilutes it: where N·L is high the colour moves towards
// the paper's, with turbulence from object-space 3D FBM (pigment pooling that sticks to the
// object); the shade is darkened only as much as `shade` asks:
//
//   albedo, normal, scene light ──► lit = clamp((N·L + a − 1)/a, 0, 1)
//   ──► cangiante C_c = albedo + clamp(cangiante · lit, 0, 1)   (the lit side turns lighter)
//   object position (control_map.object) ──► τ = turbulence · fbm3(p · scale)
//   ──► image = mix(C_c, paper, dil) · (1 − shade (1 − lit)),  dil = clamp(dilution · lit · (1 +
//   τ)) ──► dilution = dil (where paper_relief shows the paper)
#include <aquarelle/plugin.hpp>

#include <algorithm>
#include <cmath>
#include <iterator>
#include <string>

#include "dilution_shaders.h"

namespace {

enum Input : uint32_t { kAlbedo, kNormal, kScene, kObject };
constexpr aq_port_desc kInputs[] = {
    aq::image_port("albedo", "gbuffer.albedo (alpha 0 on the background)"),
    aq::image_port("normal", "gbuffer.normal (world, unit)"),
    aq::scene_port("scene", "the light's direction"),
    aq::optional_image_port("object",
                            "control_map.object: anchors the turbulence to objects; "
                            "unconnected: no turbulence")};
enum Output : uint32_t { kImage, kDilution, kOutputCount };
constexpr aq_port_desc kOutputs[] = {
    aq::image_port("image", "the painted colour"),
    aq::image_port("dilution", "how diluted each pixel is, [0, 1] in rgb (paper_relief's mask)")};
enum Param : uint32_t {
  kDilutionAmount,
  kArea,
  kShade,
  kTurbulence,
  kScale,
  kOctaves,
  kPaper,
  kCangiante,
  kTurbulenceBend
};
constexpr aq_param_desc kParams[] = {
    aq::float_param("dilution", 0.8, 0.0, 1.0,
                    "how far full light dilutes the colour towards the paper"),
    aq::float_param("diffuse_area", 1.0, 0.05, 1.0,
                    "a: the lit area shrinks as a falls (lit = (N.L + a - 1)/a)"),
    aq::float_param("shade", 0.25, 0.0, 1.0,
                    "how much the unlit side is darkened (0: not at all, the paper's model)"),
    aq::float_param("turbulence", 0.5, 0.0, 4.0, "pigment turbulence: FBM gain on the dilution"),
    aq::float_param("scale", 3.0, 0.01, 100.0, "turbulence FBM cells per object-space unit"),
    aq::int_param("octaves", 4, 1, 8, "turbulence FBM octaves"),
    aq::color_param("paper_color", 0.96, 0.93, 0.85, "the paper's colour (linear)"),
    aq::float_param("cangiante", 0.2, 0.0, 1.0,
                    "MNPR's cangiante: how much lighter the colour turns in the light "
                    "(C + cangiante * lit, before the dilution; 0: off)"),
    aq::float_param("turbulence_bend", 0.0, 0.0, 0.95,
                    "seed 002's cubism: the turbulence noise blends its lattice with "
                    "smoothstep(bend/2, 1 - bend/2, t) instead of Perlin's fade (the seed's "
                    "smoothstep with the wrong edges): towards 0.95 the turbulence breaks into "
                    "flat-faced blocks; 0: the usual noise")};

struct Dilution {
  int process(aq::Context& ctx) {
    const aq_scene* scene = ctx.input_scene(kScene);
    if (scene == nullptr) {
      return ctx.fail(std::string("dilution '") + ctx.node_id() +
                      "': input `scene` is not connected; connect the scene_join's `scene`");
    }
    const aq_image albedo = ctx.input_image(kAlbedo);
    aq_image targets[kOutputCount];
    for (uint32_t i = 0; i < kOutputCount; ++i) {
      if (!ctx.output_like(i, albedo, &targets[i])) return AQ_ERROR;
    }
    const GLuint program = ctx.program(shaders::dilution_frag);
    if (program == 0) return AQ_ERROR;
    const float* d = scene->light.direction;
    const double length =
        std::sqrt(double{d[0]} * d[0] + double{d[1]} * d[1] + double{d[2]} * d[2]);
    const double to_light[3] = {length > 0 ? -d[0] / length : 0.0,
                                length > 0 ? -d[1] / length : 1.0,
                                length > 0 ? -d[2] / length : 0.0};
    const bool anchored = ctx.connected(kObject);
    glUseProgram(program);
    aq::bind_texture(program, "u_albedo", 0, albedo);
    aq::bind_texture(program, "u_normal", 1, ctx.input_image(kNormal));
    aq::bind_texture(program, "u_anchor", 2, anchored ? ctx.input_image(kObject) : albedo);
    aq::set_vec3(program, "u_to_light", to_light);
    aq::set_vec3(program, "u_paper", ctx.param_vec3(kPaper));
    aq::set_float(program, "u_dilution", ctx.param_float(kDilutionAmount));
    aq::set_float(program, "u_area", ctx.param_float(kArea));
    aq::set_float(program, "u_cangiante", ctx.param_float(kCangiante));
    aq::set_float(program, "u_shade", ctx.param_float(kShade));
    aq::set_float(program, "u_turbulence", anchored ? ctx.param_float(kTurbulence) : 0.0);
    aq::set_float(program, "u_scale", ctx.param_float(kScale));
    aq::set_int(program, "u_octaves", static_cast<int>(ctx.param_int(kOctaves)));
    aq::set_float(program, "u_bend", ctx.param_float(kTurbulenceBend));
    if (!ctx.bind_targets(targets, kOutputCount)) return AQ_ERROR;
    // Damage tracking: every pixel reads only its own texels, so with the outputs kept and the
    // same light only the pixels whose inputs changed are redrawn (the fish, not the floor's
    // FBM).
    aq::Region damage = aq::Region::everything();
    const bool same_light = std::equal(std::begin(to_light), std::end(to_light), last_light_);
    if (ctx.output_kept(kImage) && ctx.output_kept(kDilution) && same_light) {
      damage = ctx.input_damage(kAlbedo);
      damage.add(ctx.input_damage(kNormal));
      if (anchored) damage.add(ctx.input_damage(kObject));
    }
    std::copy(std::begin(to_light), std::end(to_light), last_light_);
    if (!ctx.set_draw_region(damage.for_drawing())) damage = aq::Region::everything();
    ctx.raw()->host->draw_fullscreen(ctx.raw()->host_data);
    ctx.set_draw_region(aq::Region::everything());
    aq::unbind_textures(3);
    for (uint32_t i = 0; i < kOutputCount; ++i)
      if (!ctx.set_output_damage(i, damage)) return AQ_ERROR;
    return AQ_OK;
  }

  double last_light_[3] = {0.0, 0.0, 0.0};
};

}  // namespace

AQ_NODE(kDilutionNode, Dilution, "dilution", "Light",
        "MNPR watercolor reflectance: light dilutes the colour towards the paper (with "
        "object-space FBM turbulence) and lightens it (cangiante) instead of brightening it; "
        "`shade` darkens the unlit side.",
        0, kInputs, kOutputs, kParams);
AQ_PLUGIN("dilution", "1.0", &kDilutionNode)
