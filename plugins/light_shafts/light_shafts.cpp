// light_shafts: god rays in the water (seed 001 notes light streaks on the cliff wall). The
// water between the camera and each surface scatters the light the caustics focus towards the
// eye: along the view ray, the caustic texture is read where the light through each point left
// the water plane, and its excess over flat water is integrated with exponential extinction.
// The sheets of focused light run along the light's direction, so on a wall the light grazes
// they read as streaks (README).
//
//   image, position ─┐
//   scene ───────────┼─► light_shafts ─► image (+ the light the water scatters to the eye)
//   caustics ────────┘
#include <aquarelle/plugin.hpp>
#include <aquarelle/sdk/scene_math.hpp>

#include <algorithm>
#include <cmath>

#include "light_shafts_shaders.h"

namespace {

constexpr aq_port_desc kInputs[] = {
    aq::image_port("image", "the picture (after fog and environment)"),
    aq::image_port("position", "world position (gbuffer.position; alpha 1 where a surface is)"),
    aq::scene_port("scene", "camera, light direction and colour, water height, caustic tile"),
    aq::image_port("caustics", "tileable caustic texture, mean 1 (caustics.image)")};
constexpr aq_port_desc kOutputs[] = {
    aq::image_port("image", "the picture plus the light the water scatters to the eye")};
enum Param { kStrength, kExtinction, kSteps, kMaxDistance, kCausticTile };
constexpr aq_param_desc kParams[] = {
    aq::float_param("strength", 1.0, 0.0, 100.0,
                    "multiplies the scattered light (0: the picture unchanged)", 0.0, "log"),
    aq::float_param("extinction", 0.1, 0.0001, 10.0,
                    "sigma per world unit: how fast the water scatters and dims the light "
                    "(1/sigma: how far shafts reach)",
                    0.0, "log"),
    aq::int_param("steps", 24, 1, 256,
                  "segments along each view ray (cost; few steps band the shafts)"),
    aq::float_param("max_distance", 40.0, 0.0, 10000.0,
                    "longest view ray, world units (the ray of a background pixel)"),
    aq::float_param("caustic_tile", 0.0, 0.0, 1000.0,
                    "world units per caustic texture period; 0: the scene's, as cel_light")};

struct LightShafts {
  int process(aq::Context& ctx) {
    const aq_image in = ctx.input_image(0);
    const aq_scene* scene = ctx.input_scene(2);
    if (scene == nullptr) return ctx.fail("the scene input carries no scene");
    const aq_image caustics = ctx.input_image(3);
    if (caustics.width < 1 || caustics.height < 1) {
      return ctx.fail("input 'caustics' is empty; connect a `caustics` node's image");
    }
    aq_image out;
    if (!ctx.output_like(0, in, &out)) return AQ_ERROR;
    GLuint program = ctx.program(shaders::light_shafts_frag);
    if (program == 0) return AQ_ERROR;
    const aq::scene_math::CameraRays rays =
        aq::scene_math::camera_rays(scene->camera, double(in.width) / double(in.height));
    const double eye[3] = {scene->camera.position[0], scene->camera.position[1],
                           scene->camera.position[2]};
    const double light[3] = {scene->light.direction[0], scene->light.direction[1],
                             scene->light.direction[2]};
    const double color[3] = {scene->light.color[0], scene->light.color[1], scene->light.color[2]};
    const double own_tile = ctx.param_float(kCausticTile);
    glUseProgram(program);
    aq::bind_texture(program, "u_image", 0, in);
    aq::bind_texture(program, "u_position", 1, ctx.input_image(1));
    aq::bind_texture(program, "u_caustics", 2, caustics);
    aq::set_vec3(program, "u_eye", eye);
    aq::set_vec3(program, "u_forward", rays.forward);
    aq::set_vec3(program, "u_right", rays.right);
    aq::set_vec3(program, "u_up", rays.up);
    aq::set_vec2(program, "u_size", in.width, in.height);
    aq::set_vec3(program, "u_light_direction", light);
    aq::set_vec3(program, "u_light_color", color);
    aq::set_float(program, "u_water_height", scene->water_height);
    aq::set_vec2(program, "u_caustic_size", caustics.width, caustics.height);
    aq::set_float(program, "u_tile", own_tile > 0.0 ? own_tile : aq::scene_caustic_tile(*scene));
    aq::set_float(program, "u_strength", ctx.param_float(kStrength));
    aq::set_float(program, "u_extinction", ctx.param_float(kExtinction));
    aq::set_float(program, "u_max_distance", ctx.param_float(kMaxDistance));
    aq::set_int(program, "u_steps", static_cast<int>(ctx.param_int(kSteps)));
    const bool drawn = ctx.draw(out);
    aq::unbind_textures(3);
    return drawn ? AQ_OK : AQ_ERROR;
  }
};

}  // namespace

AQ_NODE(kLightShaftsNode, LightShafts, "light_shafts", "Scene",
        "God rays: the light the water scatters towards the eye where the caustics focus it, "
        "integrated along each view ray with exponential extinction (streaks along the light).",
        0, kInputs, kOutputs, kParams);
AQ_PLUGIN("light_shafts", "1.0", &kLightShaftsNode)
