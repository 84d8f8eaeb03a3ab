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
    aq::optional_image_port("panorama",
                            "equirectangular panorama (e.g. from `read`): 360 degrees of longitude "
                            "across, 180 of latitude from bottom to top"),
    aq::optional_image_port("cube_px", "cube map face seen looking along +x (right +z, up +y)"),
    aq::optional_image_port("cube_nx", "cube map face looking along -x (right -z, up +y)"),
    aq::optional_image_port("cube_py", "cube map face looking up +y (right +x, up +z)"),
    aq::optional_image_port("cube_ny", "cube map face looking down -y (right +x, up -z)"),
    aq::optional_image_port("cube_pz", "cube map face looking along +z (right -x, up +y)"),
    aq::optional_image_port("cube_nz", "cube map face looking along -z (right +x, up +y)")};
constexpr uint32_t kPanorama = 3, kFirstFace = 4;
constexpr const char* kFaceNames[6] = {"cube_px", "cube_nx", "cube_py",
                                       "cube_ny", "cube_pz", "cube_nz"};
constexpr aq_port_desc kOutputs[] = {
    aq::image_port("image", "the objects over the environment, alpha 1 on the background")};
enum Param { kRotation, kIntensity, kMissingFaceColor };
constexpr aq_param_desc kParams[] = {
    aq::float_param("rotation", 0.0, -360.0, 360.0,
                    "degrees added to the longitude (turns the panorama about the vertical)", 0.0,
                    "angle"),
    aq::float_param("intensity", 1.0, 0.0, 1000.0, "multiplies the panorama's linear colour", 0.0,
                    "log"),
    aq::color_param("missing_face_color", 0.0, 0.0, 0.0,
                    "cube map: what a face whose input is not connected shows (linear)")};

struct Environment {
  bool warned_missing = false;

  int process(aq::Context& ctx) {
    const aq_image in = ctx.input_image(0);
    const aq_scene* scene = ctx.input_scene(2);
    if (scene == nullptr) return ctx.fail("the scene input carries no scene");
    int faces = 0;
    std::string missing;
    for (uint32_t f = 0; f < 6; ++f) {
      if (ctx.connected(kFirstFace + f)) {
        ++faces;
      } else {
        missing += std::string(missing.empty() ? "" : ", ") + kFaceNames[f];
      }
    }
    const bool cube = faces > 0;
    if (!cube && !ctx.connected(kPanorama)) {
      return ctx.fail(
          "no environment image: connect input 'panorama' (an equirectangular "
          "image, e.g. from a `read` node) or the six cube_* faces");
    }
    if (cube && faces < 6 && !warned_missing) {
      ctx.warn("cube map without input(s) " + missing +
               ": looking that way shows missing_face_color; connect all six faces");
      warned_missing = true;
    }
    const aq_image panorama = cube ? in : ctx.input_image(kPanorama);
    if (panorama.width < 1 || panorama.height < 1) {
      return ctx.fail("input 'panorama' is empty; connect an image (e.g. a `read` node)");
    }
    aq_image out;
    if (!ctx.output_like(0, in, &out)) return AQ_ERROR;
    GLuint program = ctx.program(shaders::environment_frag);
    if (program == 0) return AQ_ERROR;
    const aq::scene_math::CameraRays rays =
        aq::scene_math::camera_rays(scene->camera, double(in.width) / double(in.height));
    glUseProgram(program);
    aq::bind_texture(program, "u_image", 0, in);
    aq::bind_texture(program, "u_id", 1, ctx.input_image(1));
    aq::bind_texture(program, "u_panorama", 2, panorama);
    aq::set_int(program, "u_cube", cube ? 1 : 0);
    int has_face[6];
    for (uint32_t f = 0; f < 6; ++f) {
      has_face[f] = ctx.connected(kFirstFace + f) ? 1 : 0;
      const std::string name = "u_face" + std::to_string(f);
      // An unconnected face binds the picture itself, never read (u_has_face is 0).
      aq::bind_texture(program, name.c_str(), 3 + f,
                       has_face[f] ? ctx.input_image(kFirstFace + f) : in);
    }
    glUniform1iv(glGetUniformLocation(program, "u_has_face"), 6, has_face);
    aq::set_vec3(program, "u_missing", ctx.param_vec3(kMissingFaceColor));
    aq::set_vec3(program, "u_forward", rays.forward);
    aq::set_vec3(program, "u_right", rays.right);
    aq::set_vec3(program, "u_up", rays.up);
    aq::set_vec2(program, "u_size", in.width, in.height);
    glUniform2i(glGetUniformLocation(program, "u_panorama_size"), panorama.width, panorama.height);
    aq::set_float(program, "u_rotation", ctx.param_float(kRotation) * 3.14159265358979 / 180.0);
    aq::set_float(program, "u_intensity", ctx.param_float(kIntensity));
    const bool drawn = ctx.draw(out);
    aq::unbind_textures(9);
    return drawn ? AQ_OK : AQ_ERROR;
  }
};

}  // namespace

AQ_NODE(kEnvironmentNode, Environment, "environment", "Scene",
        "The scene's surroundings from an equirectangular panorama image or six cube map faces "
        "(seed 001's skybox): background pixels (id 0) show it along their view ray.",
        0, kInputs, kOutputs, kParams);
AQ_PLUGIN("environment", "1.0", &kEnvironmentNode)
