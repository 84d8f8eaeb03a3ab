// gbuffer: rasterises a scene from its camera at the graph's resolution into the five targets
// the deferred light pass reads (Paré-Vogt & Chaid §2.3, "Scene" pass):
//
//   scene ──► [vertex buffers, uploaded once per geometry_revision] ──► one draw per mesh
//             ──► position (world xyz, w = 1 on geometry)   RGBA32F always (shadow lookups)
//                 normal   (world, unit, w = 1)            working format
//                 albedo   (linear rgb x base colour texture, a = 1; the environment's
//                           gradient with a = 0 behind the scene)   working format
//                 depth    (linear view depth, far plane on the background)  R32F
//                 id       (object_id as float, 0 on the background)         R32F
//                 surface  (normal, albedo, id and depth packed for the light) RGBA32UI
//
// The background is marked explicitly (id 0, w = 0), never by a zero normal. Texture alpha
// under a mesh's cut-off is a hole (cut-out cards).
#include <aquarelle/plugin.hpp>
#include <aquarelle/sdk/gl_raii.hpp>
#include <aquarelle/sdk/scene_gpu.hpp>
#include <aquarelle/sdk/scene_math.hpp>
#include <aquarelle/sdk/static_layer.hpp>

#include <glm/gtc/type_ptr.hpp>

#include <cstring>
#include <string>
#include <vector>

#include "gbuffer_shaders.h"
#include "mesh_coverage.hpp"

namespace {

constexpr aq_port_desc kInputs[] = {aq::scene_port("scene", "meshes, camera and light")};
enum Output { kPosition, kNormal, kAlbedo, kDepth, kId, kSurface, kOutputCount };
constexpr aq_port_desc kOutputs[] = {
    aq::image_port("position", "world position; w = 1 on geometry, 0 on the background"),
    aq::image_port("normal", "world normal (unit), facing the camera; w = 1 on geometry"),
    aq::image_port("albedo", "linear base colour; a = 1 on geometry"),
    aq::image_port("depth",
                   "linear view depth (world units along the view axis); far plane "
                   "on the background (R32F)"),
    aq::image_port("id", "object id as a float (R32F); 0 on the background"),
    aq::image_port("surface",
                   "normal, albedo, id and depth in one texel for a deferred light (RGBA32UI, "
                   "nodes/shaders/gbuffer_surface.glsl): x = the octahedral normal in 2 x 16 "
                   "bits, y = packHalf2x16(albedo.rg), z = albedo.b as a half and the id in 16 "
                   "bits, w = floatBitsToUint(depth); one read instead of four")};
enum Param { kCacheStatic };
constexpr aq_param_desc kParams[] = {aq::bool_param(
    "cache_static", true,
    "keep the meshes that did not move since the last frame in a cached layer and draw only "
    "what moved over a copy of it (the same targets)")};

class GBuffer {
 public:
  int process(aq::Context& ctx) {
    const aq_scene* scene = ctx.input_scene(0);
    if (scene == nullptr) {
      return ctx.fail(std::string("gbuffer '") + ctx.node_id() +
                      "': input `scene` is not connected; connect a scene node's `scene` port");
    }
    const int width = ctx.width(), height = ctx.height();
    const uint32_t formats[kOutputCount] = {AQ_FORMAT_RGBA32F,    ctx.working_format(),
                                            ctx.working_format(), AQ_FORMAT_R32F,
                                            AQ_FORMAT_R32F,       AQ_FORMAT_RGBA32UI};
    aq_image targets[kOutputCount];
    for (uint32_t i = 0; i < kOutputCount; ++i) {
      if (!ctx.output(i, width, height, formats[i], &targets[i])) return AQ_ERROR;
    }
    // The outputs nothing reads in this evaluation are left unwritten (no draw, clear or copy
    // into them): in the flagship the light reads `surface` and the blur `depth`, so four of
    // the six targets are skipped. A change of that set redraws everything.
    uint32_t read_mask = 0;
    for (uint32_t i = 0; i < kOutputCount; ++i) read_mask |= ctx.output_read(i) ? 1u << i : 0u;
    bool outputs_kept = false;
    const aq_image depth_buffer =
        depth_.get(ctx.raw()->gl_generation, width, height, &outputs_kept);
    for (uint32_t i = 0; i < kOutputCount; ++i) outputs_kept = outputs_kept && ctx.output_kept(i);
    outputs_kept = outputs_kept && read_mask == read_mask_;
    read_mask_ = read_mask;
    aq_image read_targets[kOutputCount];  // texture 0 where unread: the restore copies skip it
    for (uint32_t i = 0; i < kOutputCount; ++i) {
      read_targets[i] = targets[i];
      if (((read_mask >> i) & 1u) == 0) read_targets[i].texture = 0;
    }
    const std::string untextured_text =
        std::string("#define AQ_GBUFFER_TEXTURED 0\n") + shaders::gbuffer_frag.text;
    const GLuint programs[2] = {
        ctx.program(shaders::gbuffer_vert,
                    aq_shader_source{shaders::gbuffer_frag.name, untextured_text.c_str(), nullptr}),
        ctx.program(shaders::gbuffer_vert, shaders::gbuffer_frag)};
    if (programs[0] == 0 || programs[1] == 0) return AQ_ERROR;

    meshes_.update(*scene, ctx.raw()->gl_generation);
    const glm::mat4 view = aq::scene_math::camera_view(scene->camera);
    const glm::mat4 projection = aq::scene_math::camera_projection(
        scene->camera, static_cast<float>(width) / static_cast<float>(height));
    const Frame frame{*scene, view, projection, programs};

    // Meshes that did not move since the last frame come from the cached layer (background
    // included); only what moved (the fish, the swaying seaweed) is drawn each frame.
    const std::vector<bool>& unchanged = unchanged_.update(*scene);
    bool layered = false;
    // Damage tracking: where the outputs may differ from what they held (the last and this
    // call's moving meshes over the kept layer; everything otherwise).
    aq::Region damage = aq::Region::everything();
    uint64_t layer_key = 0;
    if (unchanged_.any() && ctx.param_bool(kCacheStatic)) {
      aq::Fnv1a key;
      unchanged_.mix_into(key);
      key.mix(view);
      key.mix(projection);
      key.mix(scene->camera.far_plane);
      const bool environment = aq::scene_has_environment(*scene);
      key.mix(environment);
      key.mix(read_mask);
      if (environment) {  // the fields exist only where struct_size covers them
        key.mix(scene->environment_top);
        key.mix(scene->environment_bottom);
      }
      layer_.ensure(ctx.raw()->gl_generation, targets, kOutputCount, &depth_buffer);
      if (layer_.key == key.value) {
        layered = true;
      } else if (layer_.bind()) {
        write_only(read_mask);
        if (!draw_background(ctx, frame)) return AQ_ERROR;
        draw_meshes(frame, &unchanged, true);
        layer_.key = key.value;
        layered = true;
      }
      layer_key = key.value;
      // With the outputs as the last call left them, the layer goes back only where that
      // call's moving meshes were.
      if (layered)
        damage = drawn_.restore(layer_, read_targets, kOutputCount, &depth_buffer, outputs_kept);
    }

    if (!ctx.bind_targets(targets, kOutputCount, &depth_buffer)) return AQ_ERROR;
    write_only(read_mask);
    if (layered) {
      draw_meshes(frame, &unchanged, false);
    } else {
      drawn_.invalidate();
      if (!draw_background(ctx, frame)) return AQ_ERROR;
      draw_meshes(frame, nullptr, false);
    }
    aq::unbind_textures(1);
    if (layered) {
      drawn_.record(layer_, *scene, boxes_.world_boxes(*scene), unchanged,
                    glm::dmat4(projection) * glm::dmat4(view), width, height);
      damage.add(drawn_.moving());
    }
    // Outside the pixels the meshes' triangles may cover every target holds the background
    // (id 0): the light needs to redraw only there when the shadow map or the caustics change.
    const glm::dmat4 view_projection = glm::dmat4(projection) * glm::dmat4(view);
    const aq::Region bounds =
        coverage_.covered(*scene, boxes_.world_boxes(*scene), layered ? &unchanged : nullptr,
                          layer_key, view_projection, width, height);
    for (uint32_t i = 0; i < kOutputCount; ++i) {
      if (!ctx.set_output_bounds(i, bounds)) return AQ_ERROR;
      if (outputs_kept && !ctx.set_output_damage(i, damage)) return AQ_ERROR;
    }
    return AQ_OK;
  }

 private:
  // The bound framebuffer's draw buffers: the targets in `read_mask`, none for the others.
  static void write_only(uint32_t read_mask) {
    GLenum buffers[kOutputCount];
    for (uint32_t i = 0; i < kOutputCount; ++i)
      buffers[i] = (read_mask >> i) & 1u ? GL_COLOR_ATTACHMENT0 + i : GL_NONE;
    glDrawBuffers(kOutputCount, buffers);
  }

  struct Frame {
    const aq_scene& scene;
    glm::mat4 view, projection;
    const GLuint* programs;  // [untextured, textured]
  };

  // Clears the bound targets to the background's values (or draws the environment there).
  static bool draw_background(aq::Context& ctx, const Frame& frame) {
    const float far_plane = frame.scene.camera.far_plane;
    const float depth_one = 1.0f;
    glClearBufferfv(GL_DEPTH, 0, &depth_one);
    if (aq::scene_has_environment(frame.scene)) {
      // One pass writes the whole background (the clear values and the environment's colour):
      // on llvmpipe five clears and a pass with four targets masked cost 1.4-1.6 copy passes,
      // one pass writing all five 1.0-1.1.
      return draw_environment(ctx, frame.scene, glm::inverse(frame.projection * frame.view),
                              far_plane);
    }
    const float zero[4] = {0, 0, 0, 0};
    const float far_value[4] = {far_plane, 0, 0, 0};
    glClearBufferfv(GL_COLOR, kPosition, zero);
    glClearBufferfv(GL_COLOR, kNormal, zero);
    glClearBufferfv(GL_COLOR, kAlbedo, zero);
    glClearBufferfv(GL_COLOR, kDepth, far_value);
    glClearBufferfv(GL_COLOR, kId, zero);
    // aq_surface_pack(0, 0, 0, far plane): zero words but the depth's.
    GLuint background_words[4] = {0, 0, 0, 0};
    std::memcpy(&background_words[3], &far_plane, sizeof(float));
    glClearBufferuiv(GL_COLOR, kSurface, background_words);
    return true;
  }

  // Draws the meshes whose `unchanged` flag equals `which` (all of them when it is null).
  void draw_meshes(const Frame& frame, const std::vector<bool>* unchanged, bool which) const {
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);
    glDepthMask(GL_TRUE);
    for (int p = 0; p < 2; ++p) {
      glUseProgram(frame.programs[p]);
      aq::set_mat4(frame.programs[p], "u_view", glm::value_ptr(frame.view));
      aq::set_mat4(frame.programs[p], "u_projection", glm::value_ptr(frame.projection));
      aq::set_int(frame.programs[p], "u_base_color", 0);
    }
    const aq_scene& scene = frame.scene;
    for (uint32_t i = 0; i < scene.mesh_count; ++i) {
      if (unchanged != nullptr && (*unchanged)[i] != which) continue;
      const aq_mesh& mesh = scene.meshes[i];
      const GLuint program = frame.programs[meshes_.surface_texture(scene, i) != 0 ? 1 : 0];
      glUseProgram(program);
      glm::mat4 model = glm::make_mat4(mesh.model);
      glm::mat3 normal_matrix = glm::transpose(glm::inverse(glm::mat3(model)));
      glUniformMatrix4fv(glGetUniformLocation(program, "u_model"), 1, GL_FALSE, mesh.model);
      glUniformMatrix3fv(glGetUniformLocation(program, "u_normal_matrix"), 1, GL_FALSE,
                         glm::value_ptr(normal_matrix));
      glUniform1f(glGetUniformLocation(program, "u_object_id"), static_cast<float>(mesh.object_id));
      glUniform1f(glGetUniformLocation(program, "u_alpha_cutoff"),
                  meshes_.bind_surface(scene, i, 0));
      meshes_.draw(mesh);
    }
    glDisable(GL_DEPTH_TEST);
  }

  // The background of every target in one pass: the gradient behind the scene in albedo,
  // the values that mark the background (w = 0, id 0, depth = far plane) in the others.
  static bool draw_environment(aq::Context& ctx, const aq_scene& scene,
                               const glm::mat4& inverse_view_projection, float far_plane) {
    GLuint program = ctx.program(shaders::environment_frag);
    if (program == 0) return false;
    glDisable(GL_DEPTH_TEST);
    glUseProgram(program);
    aq::set_mat4(program, "u_inverse_view_projection", glm::value_ptr(inverse_view_projection));
    aq::set_vec3(program, "u_top", scene.environment_top);
    aq::set_vec3(program, "u_bottom", scene.environment_bottom);
    aq::set_float(program, "u_far_plane", far_plane);
    ctx.raw()->host->draw_fullscreen(ctx.raw()->host_data);
    return true;
  }

  aq::SceneMeshCache meshes_;
  aq::UnchangedMeshes unchanged_;
  aq::CachedTargets layer_;
  aq::KeptDepth depth_;
  aq::view_bounds::MeshBoxes boxes_;
  aq::DrawnOverLayer drawn_;
  gbuffer::MeshCoverage coverage_;
  uint32_t read_mask_ = 0;  // the outputs read on the last call
};

}  // namespace

AQ_NODE(kGBufferNode, GBuffer, "gbuffer", "Scene",
        "Rasterises the scene from its camera: world position, normal, albedo, linear "
        "depth and object id (0 = background), and the last three packed for the light.",
        0, kInputs, kOutputs, kParams);
AQ_PLUGIN("gbuffer", "1.0", &kGBufferNode)
