// tremor: screen-space hand tremor (MNPR / seed 002): lookups displaced by smooth noise where the
// control map's tremor channel (alpha) asks, so painted borders wobble a little and keep
// wobbling coherently from frame to frame (time is the noise's third axis).
//
//   control.a (or 1) · amplitude · perlin3(pixel / wavelength, time · speed) ──► offset
//   image sampled at pixel + offset (bilinear, clamped) ──► image
//
// amplitude 0 passes the image through; pixels whose control is 0 get their own texel.
// The geometry tremor (vertices along the normal) is the `hand_tremor` scene node beside it.
#include <aquarelle/plugin.hpp>
#include <aquarelle/sdk/scene_math.hpp>
#include <aquarelle/sdk/static_layer.hpp>

#include <cmath>
#include <vector>

#include "tremor_shaders.h"

namespace {

enum Input : uint32_t { kImage, kControl, kScene };
constexpr aq_port_desc kInputs[] = {
    aq::image_port("image", "the image to wobble"),
    aq::optional_image_port(
        "control",
        "control map: alpha is the unitless tremor mask (1 = full amplitude, at most 2); "
        "unconnected: 1"),
    aq::optional_scene_port(
        "scene",
        "the scene the control map was drawn from: only the objects that tremble are redrawn "
        "as time goes on (damage tracking); unconnected: every pixel each frame")};
constexpr aq_port_desc kOutputs[] = {aq::image_port("image", "the wobbled image")};
enum Param : uint32_t { kAmplitude, kWavelength, kSpeed };
constexpr aq_param_desc kParams[] = {
    aq::float_param("amplitude", 2.0, 0.0, 64.0,
                    "largest displacement in output pixels (times the control); 0: identity"),
    aq::float_param("wavelength", 24.0, 1.0, 4096.0, "noise feature size in output pixels"),
    aq::float_param("speed", 1.0, 0.0, 100.0,
                    "how fast the wobble changes (noise cells per second)")};

// The control's tremor mask is clamped to this (control_map writes at most 2), so a lookup
// reaches at most this times the amplitude.
constexpr double kMaxMask = 2.0;

class Tremor {
 public:
  int process(aq::Context& ctx) {
    const aq_image in = ctx.input_image(kImage);
    if (!(ctx.param_float(kAmplitude) > 0.0)) return ctx.pass_through(0, kImage) ? AQ_OK : AQ_ERROR;
    aq_image out;
    if (!ctx.output_like(0, in, &out)) return AQ_ERROR;
    const GLuint program = ctx.program(shaders::tremor_frag);
    if (program == 0) return AQ_ERROR;
    const double amplitude = ctx.param_float(kAmplitude) * ctx.render_scale();
    const double phase = ctx.time() * ctx.param_float(kSpeed);
    glUseProgram(program);
    aq::bind_texture(program, "u_image", 0, in);
    aq::bind_texture(program, "u_control", 1,
                     ctx.connected(kControl) ? ctx.input_image(kControl) : in);
    aq::set_int(program, "u_has_control", ctx.connected(kControl) ? 1 : 0);
    aq::set_float(program, "u_amplitude", amplitude);
    aq::set_float(program, "u_max_mask", kMaxMask);
    aq::set_float(program, "u_wavelength", ctx.param_float(kWavelength) * ctx.render_scale());
    aq::set_float(program, "u_phase", phase);
    aq::Region damage = damaged(ctx, out, amplitude, phase);
    last_phase_ = phase;
    if (!ctx.set_draw_region(damage.for_drawing())) damage = aq::Region::everything();
    // Drawn even when nothing changed: the host learns that the draw applies the epilogue.
    const bool drawn = ctx.draw(out);
    ctx.set_draw_region(aq::Region::everything());
    aq::unbind_textures(2);
    return drawn && ctx.set_output_damage(0, damage) ? AQ_OK : AQ_ERROR;
  }

 private:
  // Damage tracking: with the output kept, a pixel can change when a texel its lookup may reach
  // changed (the amplitude times the largest mask, one more for the bilinear read), when its
  // mask changed, or, as time goes on, when its object trembles (the control map's alpha is 0
  // elsewhere: the pixel reads its own texel); and where the fused epilogue changed.
  aq::Region damaged(aq::Context& ctx, const aq_image& out, double amplitude, double phase) {
    if (!ctx.output_kept(0)) return aq::Region::everything();
    const int reach = static_cast<int>(std::ceil(amplitude * kMaxMask)) + 2;
    aq::Region damage = ctx.input_damage(kImage).dilated(reach, reach, out.width, out.height);
    if (ctx.connected(kControl)) {
      const aq_image control = ctx.input_image(kControl);
      if (control.width != out.width || control.height != out.height)
        return aq::Region::everything();
      damage.add(ctx.input_damage(kControl).dilated(reach, reach, out.width, out.height));
    }
    if (phase != last_phase_) damage.add(trembling(ctx, out, reach));
    damage.add(ctx.epilogue_damage());
    return damage;
  }

  // The pixels of the objects that tremble (art direction tremor > 0), their projected boxes
  // widened by `reach`; everything without the scene or the control map.
  aq::Region trembling(aq::Context& ctx, const aq_image& out, int reach) {
    const aq_scene* scene = ctx.input_scene(kScene);
    if (scene == nullptr || !ctx.connected(kControl)) return aq::Region::everything();
    const glm::dmat4 view_projection =
        glm::dmat4(aq::scene_math::camera_projection(
            scene->camera, static_cast<float>(out.width) / static_cast<float>(out.height))) *
        glm::dmat4(aq::scene_math::camera_view(scene->camera));
    const std::vector<aq::view_bounds::Box>& boxes = boxes_.world_boxes(*scene);
    std::vector<aq::PixelRect> covered;
    for (uint32_t i = 0; i < scene->mesh_count && i < boxes.size(); ++i) {
      if (!(aq::surface_art(*scene, i).tremor > 0.0f)) continue;
      covered.push_back(aq::covered_pixels(boxes[i], view_projection, out.width, out.height));
    }
    aq::Region region;
    region.add(covered);
    return region.dilated(reach, reach, out.width, out.height);
  }

  aq::view_bounds::MeshBoxes boxes_;
  double last_phase_ = std::nan("");
};

}  // namespace

AQ_NODE(kTremorNode, Tremor, "tremor", "Watercolor",
        "Screen-space hand tremor: lookups displaced by time-coherent noise where the control "
        "map's alpha asks.",
        AQ_NODE_TIME_DEPENDENT | AQ_NODE_EPILOGUE, kInputs, kOutputs, kParams);

const aq_node_desc* hand_tremor_node_desc();

AQ_PLUGIN("tremor", "1.0", &kTremorNode, hand_tremor_node_desc())
