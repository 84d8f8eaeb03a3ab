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
    const aq::scene_math::ViewFit fit = aq::scene_math::fit_to_view(
        *scene, boxes_.world_boxes(*scene),
        static_cast<float>(ctx.width()) / static_cast<float>(ctx.height()));
    const int size = ctx.param_bool(kAutoSize) ? aq::scene_math::shadow_size_for_view(
                                                     fit, scene->camera, ctx.height(), max_size)
                                               : max_size;
    aq_image depth, depth_buffer;
    if (!ctx.output(0, size, size, AQ_FORMAT_R32F, &depth)) return AQ_ERROR;
    if (!ctx.scratch(size, size, AQ_FORMAT_DEPTH32F, &depth_buffer)) return AQ_ERROR;
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
    std::vector<bool> unchanged = find_unchanged(*scene);
    const uint64_t static_key = static_casters_key(*scene, unchanged, light, size, ctx);
    const bool any_unchanged =
        std::find(unchanged.begin(), unchanged.end(), true) != unchanged.end();
    if (any_unchanged &&
        !update_static_casters(ctx, *scene, unchanged, static_key, size, program)) {
      return AQ_ERROR;
    }
    if (any_unchanged) {
      glCopyImageSubData(casters_color_.get(), GL_TEXTURE_2D, 0, 0, 0, 0, depth.texture,
                         GL_TEXTURE_2D, 0, 0, 0, 0, size, size, 1);
      glCopyImageSubData(casters_depth_.get(), GL_TEXTURE_2D, 0, 0, 0, 0, depth_buffer.texture,
                         GL_TEXTURE_2D, 0, 0, 0, 0, size, size, 1);
    }
    if (!ctx.bind_targets(&depth, 1, &depth_buffer)) return AQ_ERROR;
    if (!any_unchanged) clear_targets();
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);
    glDepthMask(GL_TRUE);
    glUseProgram(program);
    draw_meshes(*scene, unchanged, false, program);
    glDisable(GL_DEPTH_TEST);
    aq::unbind_textures(1);  // the cut-out texture unit, and the program
    return AQ_OK;
  }

 private:
  static void clear_targets() {
    const float one = 1.0f;
    const float nothing[4] = {1.0f, 0.0f, 0.0f, 0.0f};
    glClearBufferfv(GL_COLOR, 0, nothing);
    glClearBufferfv(GL_DEPTH, 0, &one);
  }

  void draw_meshes(const aq_scene& scene, const std::vector<bool>& unchanged, bool which,
                   GLuint program) const {
    const GLint model_location = glGetUniformLocation(program, "u_model");
    const GLint cutoff_location = glGetUniformLocation(program, "u_alpha_cutoff");
    aq::set_int(program, "u_base_color", 0);
    for (uint32_t i = 0; i < scene.mesh_count; ++i) {
      if (unchanged[i] != which) continue;
      glUniformMatrix4fv(model_location, 1, GL_FALSE, scene.meshes[i].model);
      glUniform1f(cutoff_location, meshes_.bind_surface(scene, i, 0));
      meshes_.draw(scene.meshes[i]);
    }
  }

  // Which meshes have the vertex data and placement they had on the previous call.
  std::vector<bool> find_unchanged(const aq_scene& scene) {
    std::vector<bool> unchanged(scene.mesh_count, false);
    std::vector<MeshState> now(scene.mesh_count);
    for (uint32_t i = 0; i < scene.mesh_count; ++i) {
      now[i].revision = scene.meshes[i].geometry_revision;
      std::copy(std::begin(scene.meshes[i].model), std::end(scene.meshes[i].model),
                now[i].model.begin());
      unchanged[i] = i < previous_.size() && previous_[i] == now[i];
    }
    previous_ = std::move(now);
    return unchanged;
  }

  // Everything the cached map depends on: which meshes, their data and placement, the light,
  // the biases and the size.
  static uint64_t static_casters_key(const aq_scene& scene, const std::vector<bool>& unchanged,
                                     const glm::mat4& light, int size, aq::Context& ctx) {
    uint64_t key = 1469598103934665603ull;
    auto mix = [&key](const void* data, size_t bytes) {
      const auto* p = static_cast<const unsigned char*>(data);
      for (size_t i = 0; i < bytes; ++i) key = (key ^ p[i]) * 1099511628211ull;
    };
    for (uint32_t i = 0; i < scene.mesh_count; ++i) {
      if (!unchanged[i]) continue;
      mix(&i, sizeof(i));
      mix(&scene.meshes[i].geometry_revision, sizeof(uint64_t));
      mix(scene.meshes[i].model, sizeof(scene.meshes[i].model));
    }
    mix(glm::value_ptr(light), sizeof(float) * 16);
    mix(&size, sizeof(size));
    for (Param p : {kSlopeBias, kConstantBias, kMaxBias}) {
      const double value = ctx.param_float(p);
      mix(&value, sizeof(value));
    }
    return key;
  }

  // Renders the unchanged meshes into the cached map when what it depends on changed.
  bool update_static_casters(aq::Context& ctx, const aq_scene& scene,
                             const std::vector<bool>& unchanged, uint64_t key, int size,
                             GLuint program) {
    const uint32_t generation = ctx.raw()->gl_generation;
    if (generation != casters_generation_ || size != casters_size_) {
      if (generation != casters_generation_) {
        casters_color_.forget();  // names of an old context mean nothing here
        casters_depth_.forget();
        casters_framebuffer_.forget();
      }
      glTextureStorage2D(casters_color_.create(), 1, GL_R32F, size, size);
      glTextureStorage2D(casters_depth_.create(), 1, GL_DEPTH_COMPONENT32F, size, size);
      const GLuint framebuffer = casters_framebuffer_.create();
      glNamedFramebufferTexture(framebuffer, GL_COLOR_ATTACHMENT0, casters_color_.get(), 0);
      glNamedFramebufferTexture(framebuffer, GL_DEPTH_ATTACHMENT, casters_depth_.get(), 0);
      casters_generation_ = generation;
      casters_size_ = size;
      casters_key_ = 0;
    }
    if (key == casters_key_) return true;
    glBindFramebuffer(GL_FRAMEBUFFER, casters_framebuffer_.get());
    if (glCheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE) {
      glBindFramebuffer(GL_FRAMEBUFFER, 0);
      ctx.fail("shadowmap: the cached caster framebuffer is incomplete");
      return false;
    }
    glViewport(0, 0, size, size);
    clear_targets();
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);
    glDepthMask(GL_TRUE);
    glUseProgram(program);
    draw_meshes(scene, unchanged, true, program);
    glDisable(GL_DEPTH_TEST);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    casters_key_ = key;
    return true;
  }

  struct MeshState {
    uint64_t revision = 0;
    std::array<float, 16> model{};
    bool operator==(const MeshState&) const = default;
  };

  aq::SceneMeshCache meshes_;
  aq::view_bounds::MeshBoxes boxes_;
  std::vector<MeshState> previous_;
  aq::gl::Texture casters_color_;
  aq::gl::Texture casters_depth_;
  aq::gl::Framebuffer casters_framebuffer_;
  uint32_t casters_generation_ = 0;
  int casters_size_ = 0;
  uint64_t casters_key_ = 0;
};

}  // namespace

AQ_NODE(kShadowMapNode, ShadowMap, "shadowmap", "Light",
        "Depth of the scene from its light (orthographic, fitted to the receivers in view), "
        "with slope-scaled bias.",
        0, kInputs, kOutputs, kParams);
AQ_PLUGIN("shadowmap", "1.0", &kShadowMapNode)
