// environment: the scene's surroundings from an image file (seed 001's skybox, Coleman &
// Dodson), behind the objects: every background pixel (id 0) shows the equirectangular
// panorama along its view ray. The panorama comes from a `read` node, so it goes through the
// same OpenImageIO / OpenColorIO path as every image (sRGB files to scene-linear).
//
//   image, id ─┐
//   scene ─────┼─► environment ─► image (objects kept, background = panorama(view ray))
//   panorama ──┘
#include <aquarelle/plugin.hpp>
#include <aquarelle/sdk/scene_math.hpp>

#include <algorithm>
#include <cmath>
#include <string>

#include "environment_shaders.h"

namespace {

constexpr aq_port_desc kInputs[] = {
    aq::image_port("image", "the picture of the objects (kept where id is not 0)"),
    aq::image_port("id", "object ids (R32F holding integers, 0 = background)"),
    aq::scene_port("scene", "the scene whose camera looks at the environment"),
    aq::image_port("panorama",
                   "equirectangular panorama (e.g. from `read`): 360 degrees of longitude across, "
                   "180 of latitude from bottom to top")};
constexpr aq_port_desc kOutputs[] = {
    aq::image_port("image", "the objects over the environment, alpha 1 on the background")};
enum Param { kRotation, kIntensity };
constexpr aq_param_desc kParams[] = {
    aq::float_param("rotation", 0.0, -360.0, 360.0,
                    "degrees added to the longitude (turns the panorama about the vertical)", 0.0,
                    "angle"),
    aq::float_param("intensity", 1.0, 0.0, 1000.0, "multiplies the panorama's linear colour", 0.0,
                    "log")};

struct Environment {
  int process(aq::Context& ctx) {
    const aq_image in = ctx.input_image(0);
    const aq_image panorama = ctx.input_image(3);
    const aq_scene* scene = ctx.input_scene(2);
    if (scene == nullptr) return ctx.fail("the scene input carries no scene");
    if (panorama.width < 1 || panorama.height < 1) {
      return ctx.fail("input 'panorama' is empty; connect an image (e.g. a `read` node)");
    }
    aq_image out;
    if (!ctx.output_like(0, in, &out)) return AQ_ERROR;
    GLuint program = ctx.program(shaders::environment_frag);
    if (program == 0) return AQ_ERROR;
    // The camera's basis from its view matrix (rows: right, up, -forward), as the g-buffer
    // sees it; the field of view clamped as camera_projection clamps it.
    const glm::mat4 view = aq::scene_math::camera_view(scene->camera);
    const double fov = std::clamp(double(scene->camera.fov_y_degrees), 1.0, 179.0);
    const double tan_half = std::tan(fov * 3.14159265358979 / 360.0);
    const double aspect = double(in.width) / double(in.height);
    const double forward[3] = {-view[0][2], -view[1][2], -view[2][2]};
    const double right[3] = {view[0][0] * tan_half * aspect, view[1][0] * tan_half * aspect,
                             view[2][0] * tan_half * aspect};
    const double up[3] = {view[0][1] * tan_half, view[1][1] * tan_half, view[2][1] * tan_half};
    glUseProgram(program);
    aq::bind_texture(program, "u_image", 0, in);
    aq::bind_texture(program, "u_id", 1, ctx.input_image(1));
    aq::bind_texture(program, "u_panorama", 2, panorama);
    aq::set_vec3(program, "u_forward", forward);
    aq::set_vec3(program, "u_right", right);
    aq::set_vec3(program, "u_up", up);
    aq::set_vec2(program, "u_size", in.width, in.height);
    glUniform2i(glGetUniformLocation(program, "u_panorama_size"), panorama.width, panorama.height);
    aq::set_float(program, "u_rotation", ctx.param_float(kRotation) * 3.14159265358979 / 180.0);
    aq::set_float(program, "u_intensity", ctx.param_float(kIntensity));
    const bool drawn = ctx.draw(out);
    aq::unbind_textures(3);
    return drawn ? AQ_OK : AQ_ERROR;
  }
};

}  // namespace

AQ_NODE(kEnvironmentNode, Environment, "environment", "Scene",
        "The scene's surroundings from an equirectangular panorama image (seed 001's skybox): "
        "background pixels (id 0) show it along their view ray.",
        0, kInputs, kOutputs, kParams);
AQ_PLUGIN("environment", "1.0", &kEnvironmentNode)
