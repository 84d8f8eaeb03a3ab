// control_map: MNPR's art-direction image (seed 002, Montesdeoca et al. 2017): the scene is
// rasterised once more from its camera, each object writing its own amounts, so every later
// screen-space pass (bleeding, edge darkening, tremor) reads what the artist asked for per pixel:
//
//   scene ──► per mesh: aq::surface_art (object node's bleed, edge darkening, tremor, FBM)
//         ──► control  r bleed · f_b   g edge darkening · f_e   b grazing 1 − |N·V|
//                      a f_t where the object trembles (unitless: the screen tremor's pixels ×)
//             object   object-space position (w = 1 on geometry): anchors noise to objects
//
// f = clamp(1 + 2 · fbm_density · fbm3(object position · fbm_scale), 0, 2), one lattice offset
// per channel, so the amounts vary along an object and stay on it when it moves. The background
// is 0 in every channel. Cut-outs are holes as in the gbuffer; same transforms, same pixels.
#include <aquarelle/plugin.hpp>
#include <aquarelle/sdk/scene_gpu.hpp>
#include <aquarelle/sdk/scene_math.hpp>
#include <aquarelle/sdk/static_layer.hpp>

#include <glm/gtc/type_ptr.hpp>

#include <string>
#include <vector>

#include "control_map_shaders.h"

namespace {

constexpr aq_port_desc kInputs[] = {aq::scene_port("scene", "objects with their art direction")};
enum Output { kControl, kObject, kOutputCount };
constexpr aq_port_desc kOutputs[] = {
    aq::image_port("control",
                   "r bleed, g edge darkening, b grazing (1 - |N.V|), a tremor mask (unitless, 1 = "
                   "full, FBM-varied; 0 where the object has no tremor); 0 on the background"),
    aq::image_port("object", "object-space position (xyz), w = 1 on geometry (RGBA32F)")};
enum Param { kOctaves, kCacheStatic };
constexpr aq_param_desc kParams[] = {
    aq::int_param("octaves", 4, 1, 8, "octaves of the object-space FBM variation"),
    aq::bool_param("cache_static", true,
                   "keep the meshes that did not move since the last frame in a cached layer and "
                   "draw only what moved over a copy of it (the same targets)")};

class ControlMap {
 public:
  int process(aq::Context& ctx) {
    const aq_scene* scene = ctx.input_scene(0);
    if (scene == nullptr) {
      return ctx.fail(std::string("control_map '") + ctx.node_id() +
                      "': input `scene` is not connected; connect a scene_join's `scene` port");
    }
    const int width = ctx.width(), height = ctx.height();
    aq_image targets[kOutputCount];
    if (!ctx.output(kControl, width, height, ctx.working_format(), &targets[kControl]) ||
        !ctx.output(kObject, width, height, AQ_FORMAT_RGBA32F, &targets[kObject])) {
      return AQ_ERROR;
    }
    bool outputs_kept = false;
    const aq_image depth_buffer =
        depth_.get(ctx.raw()->gl_generation, width, height, &outputs_kept);
    for (uint32_t i = 0; i < kOutputCount; ++i) outputs_kept = outputs_kept && ctx.output_kept(i);
    const GLuint depth_program =
        ctx.program(shaders::control_map_vert, shaders::control_map_depth_frag);
    const GLuint program = ctx.program(shaders::control_map_vert, shaders::control_map_frag);
    if (program == 0 || depth_program == 0) return AQ_ERROR;
    meshes_.update(*scene, ctx.raw()->gl_generation);
    const glm::mat4 view = aq::scene_math::camera_view(scene->camera);
    const glm::mat4 projection = aq::scene_math::camera_projection(
        scene->camera, static_cast<float>(width) / static_cast<float>(height));
    const Frame frame{*scene,        view,    projection,
                      depth_program, program, static_cast<int>(ctx.param_int(kOctaves))};

    // As the gbuffer does: meshes that did not move since the last frame (nor changed their art
    // direction) come from a cached layer, and only what moved pays the FBMs each frame. The
    // depth test keeps the nearest surface whatever the order: the same targets.
    const std::vector<bool>& unchanged = unchanged_.update(*scene);
    aq::Region damage = aq::Region::everything();
    bool layered = false;
    if (unchanged_.any() && ctx.param_bool(kCacheStatic)) {
      aq::Fnv1a key;
      unchanged_.mix_into(key);
      for (uint32_t i = 0; i < scene->mesh_count; ++i) {
        if (!unchanged[i]) continue;
        const aq::ArtDirection art = aq::surface_art(*scene, i);
        key.mix(art.bleed), key.mix(art.edge_darkening), key.mix(art.tremor);
        key.mix(art.fbm_density), key.mix(art.fbm_scale);
      }
      key.mix(view);
      key.mix(projection);
      key.mix(frame.octaves);
      layer_.ensure(ctx.raw()->gl_generation, targets, kOutputCount, &depth_buffer);
      if (layer_.key == key.value) {
        layered = true;
      } else if (layer_.bind()) {
        clear_bound();
        draw_passes(frame, &unchanged, true);
        layer_.key = key.value;
        layered = true;
      }
      if (layered)
        damage = drawn_.restore(layer_, targets, kOutputCount, &depth_buffer, outputs_kept);
    }
    if (!ctx.bind_targets(targets, kOutputCount, &depth_buffer)) return AQ_ERROR;
    if (layered) {
      draw_passes(frame, &unchanged, false);
      drawn_.record(layer_, *scene, boxes_.world_boxes(*scene), unchanged,
                    glm::dmat4(projection) * glm::dmat4(view), width, height);
      damage.add(drawn_.moving());
    } else {
      drawn_.invalidate();
      clear_bound();
      draw_passes(frame, nullptr, false);
    }
    aq::unbind_textures(1);
    for (uint32_t i = 0; i < kOutputCount; ++i) {
      if (outputs_kept && !ctx.set_output_damage(i, damage)) return AQ_ERROR;
    }
    return AQ_OK;
  }

 private:
  struct Frame {
    const aq_scene& scene;
    glm::mat4 view, projection;
    GLuint depth_program, program;
    int octaves;
  };

  // The background: 0 in every channel, the far depth.
  static void clear_bound() {
    const float zero[4] = {0, 0, 0, 0};
    const float depth_one = 1.0f;
    glClearBufferfv(GL_COLOR, kControl, zero);
    glClearBufferfv(GL_COLOR, kObject, zero);
    glClearBufferfv(GL_DEPTH, 0, &depth_one);
  }

  // The meshes whose `unchanged` flag equals `which` (all of them when it is null) into the
  // bound targets: a depth pre-pass, then the art direction where the nearest surface is.
  void draw_passes(const Frame& frame, const std::vector<bool>* unchanged, bool which) {
    glEnable(GL_DEPTH_TEST);
    // Pass 1: depth only (cut-outs applied), so pass 2's FBM runs once per visible pixel.
    glDepthFunc(GL_LESS);
    glDepthMask(GL_TRUE);
    glColorMask(GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);
    draw_meshes(frame, frame.depth_program, /*with_art=*/false, unchanged, which);
    glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
    // Pass 2: the art direction where the nearest surface is.
    glDepthFunc(GL_EQUAL);
    glDepthMask(GL_FALSE);
    draw_meshes(frame, frame.program, /*with_art=*/true, unchanged, which);
    glDepthMask(GL_TRUE);
    glDepthFunc(GL_LESS);
    glDisable(GL_DEPTH_TEST);
  }

  void draw_meshes(const Frame& frame, GLuint program, bool with_art,
                   const std::vector<bool>* unchanged, bool which) {
    const aq_scene& scene = frame.scene;
    glUseProgram(program);
    aq::set_mat4(program, "u_view", glm::value_ptr(frame.view));
    aq::set_mat4(program, "u_projection", glm::value_ptr(frame.projection));
    aq::set_int(program, "u_base_color", 0);
    if (with_art) {
      aq::set_vec3(program, "u_camera", scene.camera.position);
      aq::set_int(program, "u_octaves", frame.octaves);
    }
    const GLint model_location = glGetUniformLocation(program, "u_model");
    const GLint normal_location = glGetUniformLocation(program, "u_normal_matrix");
    const GLint amounts_location = glGetUniformLocation(program, "u_amounts");
    const GLint density_location = glGetUniformLocation(program, "u_fbm_density");
    const GLint scale_location = glGetUniformLocation(program, "u_fbm_scale");
    const GLint cutoff_location = glGetUniformLocation(program, "u_alpha_cutoff");
    for (uint32_t i = 0; i < scene.mesh_count; ++i) {
      if (unchanged != nullptr && (*unchanged)[i] != which) continue;
      const aq_mesh& mesh = scene.meshes[i];
      const glm::mat4 model = glm::make_mat4(mesh.model);
      const glm::mat3 normal_matrix = glm::transpose(glm::inverse(glm::mat3(model)));
      glUniformMatrix4fv(model_location, 1, GL_FALSE, mesh.model);
      glUniformMatrix3fv(normal_location, 1, GL_FALSE, glm::value_ptr(normal_matrix));
      if (with_art) {
        const aq::ArtDirection art = aq::surface_art(scene, i);
        glUniform4f(amounts_location, art.bleed, art.edge_darkening, art.tremor, 0.0f);
        glUniform1f(density_location, art.fbm_density);
        glUniform1f(scale_location, art.fbm_scale);
      }
      const float cutoff = meshes_.bind_surface(scene, i, 0);
      if (!with_art) glUniform1f(cutoff_location, cutoff);
      meshes_.draw(mesh);
    }
  }

  aq::SceneMeshCache meshes_;
  aq::UnchangedMeshes unchanged_;
  aq::CachedTargets layer_;
  aq::KeptDepth depth_;
  aq::view_bounds::MeshBoxes boxes_;
  aq::DrawnOverLayer drawn_;
};

}  // namespace

AQ_NODE(kControlMapNode, ControlMap, "control_map", "Scene",
        "MNPR control map: per-pixel bleed, edge darkening, grazing angle (1 - |N.V|) and tremor "
        "from each object's art direction, varied by object-space FBM; and object-space "
        "positions for noise that sticks to objects.",
        0, kInputs, kOutputs, kParams);
AQ_PLUGIN("control_map", "1.0", &kControlMapNode)
