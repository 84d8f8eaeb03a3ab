// shadowmap: depth of the scene seen from its directional light (Paré-Vogt & Chaid §2.3),
// through an orthographic projection fitted to the scene's bounds. The matrix comes from
// aquarelle/scene_math.hpp so cel_light, which reads this map, uses exactly the same one.
//
//   scene ──► light_view_projection(scene) ──► draw every mesh ──► depth (R32F, size x size)
//             value = window depth in [0, 1] + slope-scaled bias; 1 where nothing is
//
// A point P is in shadow when 0.5 * (M * P).z / w + 0.5 > depth at its texel (M the matrix).
#include <aquarelle/plugin.hpp>
#include <aquarelle/scene_gpu.hpp>
#include <aquarelle/scene_math.hpp>

#include <glm/gtc/type_ptr.hpp>

#include <algorithm>
#include <cmath>
#include <string>

#include "shadowmap_shaders.h"

namespace {

constexpr aq_port_desc kInputs[] = {aq::scene_port("scene", "meshes and the light")};
constexpr aq_port_desc kOutputs[] = {
    aq::image_port("depth", "light-space depth in [0, 1] with bias (R32F); 1 = nothing")};
enum Param { kSize, kSlopeBias, kConstantBias, kMaxBias };
constexpr aq_param_desc kParams[] = {
    aq::int_param("size", 1024, 16, 8192, "shadow map width and height in texels"),
    aq::float_param("slope_bias", 2.0, 0.0, 20.0,
                    "bias in multiples of the depth change across one texel (acne at grazing "
                    "light needs >= 1.5 with PCF)"),
    aq::float_param("constant_bias", 0.005, 0.0, 1.0, "constant bias in world units"),
    aq::float_param("max_bias", 0.5, 0.0, 100.0,
                    "cap on the total bias in world units (edge-on triangles)")};

class ShadowMap {
 public:
  int process(aq::Context& ctx) {
    const aq_scene* scene = ctx.input_scene(0);
    if (scene == nullptr) {
      return ctx.fail(std::string("shadowmap '") + ctx.node_id() +
                      "': input `scene` is not connected; connect a scene node's `scene` port");
    }
    // `size` is for a full-size render: a proxy render needs the texels per screen pixel of
    // the full one, so the map shrinks with the render scale.
    const int size =
        std::max(16, static_cast<int>(std::lround(static_cast<double>(ctx.param_int(kSize)) *
                                                  ctx.render_scale())));
    aq_image depth, depth_buffer;
    if (!ctx.output(0, size, size, AQ_FORMAT_R32F, &depth)) return AQ_ERROR;
    if (!ctx.scratch(size, size, AQ_FORMAT_DEPTH32F, &depth_buffer)) return AQ_ERROR;
    GLuint program = ctx.program(shaders::shadow_vert, shaders::shadow_frag);
    if (program == 0) return AQ_ERROR;

    meshes_.update(*scene, ctx.raw()->gl_generation);
    if (!ctx.bind_targets(&depth, 1, &depth_buffer)) return AQ_ERROR;
    const float one = 1.0f;
    const float nothing[4] = {1.0f, 0.0f, 0.0f, 0.0f};
    glClearBufferfv(GL_COLOR, 0, nothing);
    glClearBufferfv(GL_DEPTH, 0, &one);

    glm::mat4 light = aq::scene_math::light_view_projection(*scene);
    // Window depth per world unit along the light: the ortho depth is linear in distance.
    glm::vec3 direction = aq::scene_math::light_direction(*scene);
    glm::vec3 depth_row(light[0][2], light[1][2], light[2][2]);
    const double depth_per_world = 0.5 * std::abs(glm::dot(depth_row, direction));

    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);
    glDepthMask(GL_TRUE);
    glUseProgram(program);
    aq::set_mat4(program, "u_light_view_projection", glm::value_ptr(light));
    aq::set_float(program, "u_slope_bias", ctx.param_float(kSlopeBias));
    aq::set_float(program, "u_constant_bias", ctx.param_float(kConstantBias) * depth_per_world);
    aq::set_float(program, "u_max_bias", ctx.param_float(kMaxBias) * depth_per_world);
    const GLint model_location = glGetUniformLocation(program, "u_model");
    for (uint32_t i = 0; i < scene->mesh_count; ++i) {
      glUniformMatrix4fv(model_location, 1, GL_FALSE, scene->meshes[i].model);
      meshes_.draw(scene->meshes[i]);
    }
    glDisable(GL_DEPTH_TEST);
    glUseProgram(0);
    return AQ_OK;
  }

 private:
  aq::SceneMeshCache meshes_;
};

}  // namespace

AQ_NODE(kShadowMapNode, ShadowMap, "shadowmap", "Light",
        "Depth of the scene from its light (orthographic, fitted to the scene bounds), with "
        "slope-scaled bias.",
        0, kInputs, kOutputs, kParams);
AQ_PLUGIN("shadowmap", "1.0", &kShadowMapNode)
