// shadowmap: depth of the scene seen from its directional light (Paré-Vogt & Chaid §2.3),
// through an orthographic projection fitted to the receivers the camera can see (the scene's
// depth range, so casters out of view still cast). The matrix comes from
// aquarelle/sdk/scene_math.hpp so cel_light, which reads this map, uses exactly the same one.
//
//   scene ──► fit_to_view ──► light_view_projection(scene, fit, size) ──► draw every mesh
//                                                    ──► depth (R32F, size x size)
//             value = window depth in [0, 1] + slope-scaled bias; 1 where nothing is
//
// A point P is in shadow when 0.5 * (M * P).z / w + 0.5 > depth at its texel (M the matrix).
#include <aquarelle/plugin.hpp>
#include <aquarelle/sdk/gl_raii.hpp>
#include <aquarelle/sdk/scene_gpu.hpp>
#include <aquarelle/sdk/scene_math.hpp>
#include <aquarelle/sdk/static_layer.hpp>

#include <glm/gtc/type_ptr.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <string>
#include <vector>

#include "shadowmap_shaders.h"

namespace {

constexpr aq_port_desc kInputs[] = {aq::scene_port("scene", "meshes and the light")};
constexpr aq_port_desc kOutputs[] = {
    aq::image_port("depth", "light-space depth in [0, 1] with bias (R32F); 1 = nothing")};
enum Param { kSize, kSlopeBias, kConstantBias, kMaxBias, kAutoSize };
constexpr aq_param_desc kParams[] = {
    aq::int_param("size", 1024, 16, 8192,
                  "shadow map width and height in texels (the largest, with auto_size)"),
    aq::float_param("slope_bias", 2.0, 0.0, 20.0,
                    "bias in multiples of the depth change across one texel (acne at grazing "
                    "light needs >= 1.5 with PCF)"),
    aq::float_param("constant_bias", 0.005, 0.0, 1.0, "constant bias in world units"),
    aq::float_param("max_bias", 0.5, 0.0, 100.0,
                    "cap on the total bias in world units (edge-on triangles)"),
    aq::bool_param("auto_size", true,
                   "size the map for about one texel per screen pixel at the nearest receiver "
                   "in view (at most `size`)")};

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
    const int max_size =
        std::max(16, static_cast<int>(std::lround(static_cast<double>(ctx.param_int(kSize)) *
                                                  ctx.render_scale())));
    const std::vector<aq::view_bounds::Box>& world_boxes = boxes_.world_boxes(*scene);
    const aq::scene_math::ViewFit fit = aq::scene_math::fit_to_view(
        *scene, world_boxes, static_cast<float>(ctx.width()) / static_cast<float>(ctx.height()));
    const int size = ctx.param_bool(kAutoSize) ? aq::scene_math::shadow_size_for_view(
                                                     fit, scene->camera, ctx.height(), max_size)
                                               : max_size;
    aq_image depth;
    if (!ctx.output(0, size, size, AQ_FORMAT_R32F, &depth)) return AQ_ERROR;
    bool kept = false;
    const aq_image depth_buffer = depth_buffer_.get(ctx.raw()->gl_generation, size, size, &kept);
    kept = kept && ctx.output_kept(0);
    GLuint program = ctx.program(shaders::shadow_vert, shaders::shadow_frag);
    if (program == 0) return AQ_ERROR;

    meshes_.update(*scene, ctx.raw()->gl_generation);
    glm::mat4 light = aq::scene_math::light_view_projection(*scene, fit, size);
    // Window depth per world unit along the light: the ortho depth is linear in distance.
    glm::vec3 direction = aq::scene_math::light_direction(*scene);
    glm::vec3 depth_row(light[0][2], light[1][2], light[2][2]);
    const double depth_per_world = 0.5 * std::abs(glm::dot(depth_row, direction));

    glUseProgram(program);
    aq::set_mat4(program, "u_light_view_projection", glm::value_ptr(light));
    aq::set_float(program, "u_slope_bias", ctx.param_float(kSlopeBias));
    aq::set_float(program, "u_constant_bias", ctx.param_float(kConstantBias) * depth_per_world);
    aq::set_float(program, "u_max_bias", ctx.param_float(kMaxBias) * depth_per_world);

    // Meshes unchanged since the last frame (same vertex data, same placement) are drawn once
    // into a cached map; each frame copies it and draws only what moved (fish, swaying weed).
    // The depth test keeps the nearest surface whatever the order, so the map is the same.
    const std::vector<bool>& unchanged = unchanged_.update(*scene);
    bool layered = false;
    // Damage tracking: the texels that may differ from what the kept map held (the last and
    // this call's moving casters over the same layer; everything otherwise), for readers that
    // can use them and for `render --stats`.
    aq::Region damage = aq::Region::everything();
    if (unchanged_.any()) {
      aq::Fnv1a key;
      unchanged_.mix_into(key);
      key.mix(light);
      key.mix(size);
      for (Param p : {kSlopeBias, kConstantBias, kMaxBias}) key.mix(ctx.param_float(p));
      layer_.ensure(ctx.raw()->gl_generation, &depth, 1, &depth_buffer);
      if (layer_.key == key.value) {
        layered = true;
      } else if (layer_.bind()) {
        clear_targets();
        draw_meshes(*scene, &unchanged, true, program);
        layer_.key = key.value;
        layered = true;
      }
      // With the map as the last call left it, the layer goes back only where that call's
      // moving casters were.
      if (layered) damage = drawn_.restore(layer_, &depth, 1, &depth_buffer, kept);
    }
    if (!ctx.bind_targets(&depth, 1, &depth_buffer)) return AQ_ERROR;
    if (!layered) {
      drawn_.invalidate();
      clear_targets();
    }
    draw_meshes(*scene, layered ? &unchanged : nullptr, false, program);
    aq::unbind_textures(1);  // the cut-out texture unit, and the program
    if (layered) {
      drawn_.record(layer_, *scene, world_boxes, unchanged, glm::dmat4(light), size, size);
      damage.add(drawn_.moving());
    }
    return kept && !ctx.set_output_damage(0, damage) ? AQ_ERROR : AQ_OK;
  }

 private:
  static void clear_targets() {
    const float one = 1.0f;
    const float nothing[4] = {1.0f, 0.0f, 0.0f, 0.0f};
    glClearBufferfv(GL_COLOR, 0, nothing);
    glClearBufferfv(GL_DEPTH, 0, &one);
  }

  // Draws the meshes whose `unchanged` flag equals `which` (all of them when it is null).
  void draw_meshes(const aq_scene& scene, const std::vector<bool>* unchanged, bool which,
                   GLuint program) const {
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);
    glDepthMask(GL_TRUE);
    glUseProgram(program);
    const GLint model_location = glGetUniformLocation(program, "u_model");
    const GLint cutoff_location = glGetUniformLocation(program, "u_alpha_cutoff");
    aq::set_int(program, "u_base_color", 0);
    for (uint32_t i = 0; i < scene.mesh_count; ++i) {
      if (unchanged != nullptr && (*unchanged)[i] != which) continue;
      glUniformMatrix4fv(model_location, 1, GL_FALSE, scene.meshes[i].model);
      glUniform1f(cutoff_location, meshes_.bind_surface(scene, i, 0));
      meshes_.draw(scene.meshes[i]);
    }
    glDisable(GL_DEPTH_TEST);
  }

  aq::SceneMeshCache meshes_;
  aq::view_bounds::MeshBoxes boxes_;
  aq::UnchangedMeshes unchanged_;
  aq::CachedTargets layer_;
  aq::KeptDepth depth_buffer_;
  aq::DrawnOverLayer drawn_;
};

}  // namespace

AQ_NODE(kShadowMapNode, ShadowMap, "shadowmap", "Light",
        "Depth of the scene from its light (orthographic, fitted to the receivers in view), "
        "with slope-scaled bias.",
        0, kInputs, kOutputs, kParams);
AQ_PLUGIN("shadowmap", "1.0", &kShadowMapNode)
