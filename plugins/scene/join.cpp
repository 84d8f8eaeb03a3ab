// scene_join: gathers any number of `object` fragments (one multi-link input) with a camera, a
// light and an environment into the `scene` port gbuffer, shadowmap and cel_light read, as
// Houdini's merge or Blender's join geometry do:
//
//   objects[0..n) ──► meshes and surfaces concatenated in link order, bounds united
//   camera / light / water / environment params ──► the aq_scene's own fields
//   each object's bounds vs the camera's view ──► a warning naming the object when none of it
//                                                 can be seen (not a silent empty frame)
//
// The aq_scene and the arrays it points to live in this instance until the next process.
#include <aquarelle/plugin.hpp>
#include <aquarelle/sdk/scene_math.hpp>
#include <aquarelle/sdk/view_bounds.hpp>

#include <cmath>
#include <cstdio>
#include <map>
#include <set>
#include <string>
#include <vector>

#include "view_setup.h"

namespace {

constexpr aq_port_desc kInputs[] = {
    aq::multi_scene_port("objects", "object nodes' fragments (link as many as you like)")};
constexpr aq_port_desc kOutputs[] = {
    aq::scene_port("scene", "the joined meshes with camera, light, environment and time")};

enum Param {
  kCameraPosition,
  kCameraTarget,
  kFov,
  kLightDirection,
  kLightColor,
  kLightIntensity,
  kAmbient,
  kWaterHeight,
  kCausticTile,
  kEnvironment,
  kEnvironmentTop,
  kEnvironmentBottom
};

constexpr aq_param_desc kParams[] = {
    aq::vec3_param("camera_position", 0.0, 2.0, 6.0, -1000, 1000, "camera position (world)"),
    aq::vec3_param("camera_target", 0.0, 0.5, 0.0, -1000, 1000, "point the camera looks at"),
    AQ_SCENE_VIEW_AND_WATER_PARAMS,
    aq::enum_param("environment", "none|gradient", 1,
                   "what is seen behind the objects: nothing (id 0, cel_light's background) "
                   "or a vertical gradient in the g-buffer's albedo"),
    aq::color_param("environment_top", 0.16, 0.42, 0.52,
                    "environment colour looking straight up (linear)"),
    aq::color_param("environment_bottom", 0.02, 0.08, 0.12,
                    "environment colour looking straight down (linear)")};

class JoinNode {
 public:
  int process(aq::Context& ctx) {
    meshes_.clear();
    surfaces_.clear();
    scene_ = aq_scene{};
    scene_.struct_size = sizeof(aq_scene);
    double lo[3] = {1e300, 1e300, 1e300}, hi[3] = {-1e300, -1e300, -1e300};
    std::vector<aq::view_bounds::Box> boxes;
    const uint32_t links = ctx.link_count(0);
    for (uint32_t k = 0; k < links; ++k) {
      const aq_scene* part = ctx.input_scene(0, k);
      if (part == nullptr) continue;
      aq::view_bounds::Box box;
      for (uint32_t m = 0; m < part->mesh_count; ++m) {
        meshes_.push_back(part->meshes[m]);
        surfaces_.push_back(aq::copy_surface(*part, m));  // an older producer's is shorter
      }
      if (part->mesh_count > 0) {
        for (int c = 0; c < 3; ++c) {
          lo[c] = std::min(lo[c], static_cast<double>(part->bounds_min[c]));
          hi[c] = std::max(hi[c], static_cast<double>(part->bounds_max[c]));
        }
        box.add({part->bounds_min[0], part->bounds_min[1], part->bounds_min[2]});
        box.add({part->bounds_max[0], part->bounds_max[1], part->bounds_max[2]});
      }
      boxes.push_back(box);
    }
    fill_scene(ctx, lo, hi);
    warn_about(ctx, boxes);
    return ctx.output_scene(0, &scene_) ? AQ_OK : AQ_ERROR;
  }

 private:
  void fill_scene(const aq::Context& ctx, const double* lo, const double* hi) {
    scene_.meshes = meshes_.data();
    scene_.mesh_count = static_cast<uint32_t>(meshes_.size());
    scene_.surfaces = surfaces_.data();
    scene_.surface_struct_size = sizeof(aq_mesh_surface);
    for (int c = 0; c < 3; ++c) {
      scene_.bounds_min[c] = meshes_.empty() ? 0.0f : static_cast<float>(lo[c]);
      scene_.bounds_max[c] = meshes_.empty() ? 0.0f : static_cast<float>(hi[c]);
    }
    scene::set_camera_and_light(
        {ctx.param_vec3(kCameraPosition), ctx.param_vec3(kCameraTarget), ctx.param_float(kFov),
         ctx.param_vec3(kLightDirection), ctx.param_vec3(kLightColor),
         ctx.param_float(kLightIntensity), ctx.param_vec3(kAmbient)},
        &scene_);
    for (int c = 0; c < 3; ++c) {
      scene_.environment_top[c] = static_cast<float>(ctx.param_vec3(kEnvironmentTop)[c]);
      scene_.environment_bottom[c] = static_cast<float>(ctx.param_vec3(kEnvironmentBottom)[c]);
    }
    scene_.has_environment = ctx.param_enum(kEnvironment) == 1 ? 1u : 0u;
    scene_.time = ctx.time();
    scene_.water_height = static_cast<float>(ctx.param_float(kWaterHeight));
    scene_.caustic_tile = static_cast<float>(ctx.param_float(kCausticTile));
  }

  // Objects none of whose box lies in the camera's view, and ids used twice: said once each
  // (not every frame) until they change.
  void warn_about(const aq::Context& ctx, const std::vector<aq::view_bounds::Box>& boxes) {
    const float aspect = static_cast<float>(ctx.width()) / static_cast<float>(ctx.height());
    const auto frustum = aq::view_bounds::frustum_planes(
        aq::scene_math::camera_view_projection(scene_.camera, aspect));
    std::set<std::string> messages;
    for (size_t k = 0; k < boxes.size(); ++k) {
      const aq::view_bounds::Box& box = boxes[k];
      if (box.empty() || !aq::view_bounds::clip_box(box, frustum).empty()) continue;
      const aq_scene* part = ctx.input_scene(0, static_cast<uint32_t>(k));
      const uint32_t id = part != nullptr && part->mesh_count > 0 ? part->meshes[0].object_id : 0;
      char text[360];
      std::snprintf(text, sizeof(text),
                    "the object with id %u (link %zu of `objects`) is outside the camera's view: "
                    "its bounds are (%.3g, %.3g, %.3g) to (%.3g, %.3g, %.3g); move it or the "
                    "camera",
                    id, k, box.lo.x, box.lo.y, box.lo.z, box.hi.x, box.hi.y, box.hi.z);
      messages.insert(text);
    }
    std::map<uint32_t, int> owners;
    for (uint32_t k = 0; k < ctx.link_count(0); ++k) {
      const aq_scene* part = ctx.input_scene(0, k);
      std::set<uint32_t> ids;
      for (uint32_t m = 0; part != nullptr && m < part->mesh_count; ++m) {
        ids.insert(part->meshes[m].object_id);
      }
      for (uint32_t id : ids) ++owners[id];
    }
    for (const auto& [id, count] : owners) {
      if (count > 1) {
        messages.insert("object id " + std::to_string(id) + " is used by " + std::to_string(count) +
                        " objects: give each object its own `id` so later passes can tell them "
                        "apart");
      }
    }
    if (messages == said_) return;
    for (const std::string& message : messages) {
      if (said_.count(message) == 0) {
        ctx.warn(std::string("scene_join '") + ctx.node_id() + "': " + message);
      }
    }
    said_ = messages;
  }

  std::vector<aq_mesh> meshes_;
  std::vector<aq_mesh_surface> surfaces_;
  aq_scene scene_{};
  std::set<std::string> said_;
};

}  // namespace

AQ_NODE(kJoinNode, JoinNode, "scene_join", "Scene",
        "Joins any number of objects with a camera, a light and an environment into the scene "
        "gbuffer, shadowmap and cel_light read.",
        AQ_NODE_TIME_DEPENDENT, kInputs, kOutputs, kParams);

const aq_node_desc* join_node_desc() {
  return &kJoinNode;
}
