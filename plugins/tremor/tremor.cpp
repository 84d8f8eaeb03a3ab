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

#include "tremor_shaders.h"

namespace {

enum Input : uint32_t { kImage, kControl };
constexpr aq_port_desc kInputs[] = {
    aq::image_port("image", "the image to wobble"),
    aq::optional_image_port(
        "control",
        "control map: alpha is the unitless tremor mask (1 = full amplitude); unconnected: 1")};
constexpr aq_port_desc kOutputs[] = {aq::image_port("image", "the wobbled image")};
enum Param : uint32_t { kAmplitude, kWavelength, kSpeed };
constexpr aq_param_desc kParams[] = {
    aq::float_param("amplitude", 2.0, 0.0, 64.0,
                    "largest displacement in output pixels (times the control); 0: identity"),
    aq::float_param("wavelength", 24.0, 1.0, 4096.0, "noise feature size in output pixels"),
    aq::float_param("speed", 1.0, 0.0, 100.0,
                    "how fast the wobble changes (noise cells per second)")};

struct Tremor {
  int process(aq::Context& ctx) {
    const aq_image in = ctx.input_image(kImage);
    if (!(ctx.param_float(kAmplitude) > 0.0)) return ctx.pass_through(0, kImage) ? AQ_OK : AQ_ERROR;
    aq_image out;
    if (!ctx.output_like(0, in, &out)) return AQ_ERROR;
    const GLuint program = ctx.program(shaders::tremor_frag);
    if (program == 0) return AQ_ERROR;
    glUseProgram(program);
    aq::bind_texture(program, "u_image", 0, in);
    aq::bind_texture(program, "u_control", 1,
                     ctx.connected(kControl) ? ctx.input_image(kControl) : in);
    aq::set_int(program, "u_has_control", ctx.connected(kControl) ? 1 : 0);
    aq::set_float(program, "u_amplitude", ctx.param_float(kAmplitude) * ctx.render_scale());
    aq::set_float(program, "u_wavelength", ctx.param_float(kWavelength) * ctx.render_scale());
    aq::set_float(program, "u_phase", ctx.time() * ctx.param_float(kSpeed));
    const bool drawn = ctx.draw(out);
    aq::unbind_textures(2);
    return drawn ? AQ_OK : AQ_ERROR;
  }
};

}  // namespace

AQ_NODE(kTremorNode, Tremor, "tremor", "Watercolor",
        "Screen-space hand tremor: lookups displaced by time-coherent noise where the control "
        "map's alpha asks.",
        AQ_NODE_TIME_DEPENDENT | AQ_NODE_EPILOGUE, kInputs, kOutputs, kParams);

const aq_node_desc* hand_tremor_node_desc();

AQ_PLUGIN("tremor", "1.0", &kTremorNode, hand_tremor_node_desc())
