// scene: the node that produces the `scene` port (meshes, camera, one directional light, time)
// for gbuffer, shadowmap and cel_light. Geometry comes from a procedural preset (the seed's
// underwater scene, or small test scenes) or from a file through Assimp; normals are smoothed
// once on the CPU when the geometry is made (mesh_smoothing.hpp, Paré-Vogt & Chaid §3.2).
//
//   params (preset, path, seed, smoothing) ──► static meshes: built once, revision fixed
//   time + animation params ────────────────► animated meshes (fish, seaweed): rebuilt per
//                                              frame, a new geometry_revision each time
//   camera / light params ──────────────────► aq_scene fields only (no geometry rebuilt)
//
// The aq_scene and every array it points to live in this instance until the next process.
#include <aquarelle/plugin.hpp>
#include <aquarelle/sdk/mesh_smoothing.hpp>

#include "presets.h"
#include "revision.h"
#include "textures.h"
#include "view_setup.h"

#include <glm/gtc/type_ptr.hpp>

#include <atomic>
#include <cmath>
#include <cstring>
#include <string>
#include <vector>

namespace {

constexpr aq_port_desc kOutputs[] = {
    aq::scene_port("scene", "meshes with smoothed normals, camera, light, time")};

enum Param {
  kPreset,
  kPath,
  kSeed,
  kSmoothing,
  kCameraPosition,
  kCameraTarget,
  kFov,
  kLightDirection,
  kLightColor,
  kLightIntensity,
  kAmbient,
  kWaterHeight,
  kCausticTile,
  kFishSpeed,
  kSway
};
constexpr const char* kPresetNames[] = {"underwater",   "plane_box",   "pot", "cube",
                                        "double_plane", "three_cubes", "file"};
constexpr int kPresetFile = 6;

constexpr aq_param_desc kParams[] = {
    aq::enum_param("preset", "underwater|plane_box|pot|cube|double_plane|three_cubes|file", 0,
                   "procedural scene, or `file` to load `path`"),
    aq::path_param("path", "OBJ or glTF scene loaded when preset is `file`"),
    aq::int_param("seed", 7, 0, 2147483647, "procedural scene seed: same seed, same scene"),
    aq::int_param("smoothing", 7, 0, 64,
                  "normal smoothing iterations at load time (the seed found 7 best)"),
    aq::vec3_param("camera_position", 0.3, 2.2, 6.0, -1000, 1000, "camera position (world)"),
    aq::vec3_param("camera_target", -0.3, 0.9, -0.5, -1000, 1000, "point the camera looks at"),
    AQ_SCENE_VIEW_AND_WATER_PARAMS,
    aq::float_param("fish_speed", 0.35, 0.0, 5.0, "fish loop speed, radians per second"),
    aq::float_param("sway", 1.0, 0.0, scene::kMaxSway, "seaweed sway amplitude (0 freezes it)")};

// Unique across every mesh this plugin ever publishes (all instances), as plugin.h asks.
uint64_t new_geometry_revision() {
  return scene::new_revision();
}

void smooth(scene::MeshData& mesh, int iterations) {
  aq::mesh::SmoothingOptions options;
  options.iterations = iterations;
  aq::mesh::smooth_normals(mesh.positions, mesh.indices, mesh.normals, options);
}

struct PublishedMesh {
  scene::MeshData data;
  uint64_t revision = 0;
};

class SceneNode {
 public:
  int process(aq::Context& ctx) {
    if (!update_static(ctx)) return AQ_ERROR;
    update_animated(ctx);
    publish(ctx);
    return ctx.output_scene(0, &scene_) ? AQ_OK : AQ_ERROR;
  }

 private:
  struct StaticKey {
    int64_t preset = -1;
    std::string path;
    int64_t seed = 0;
    int64_t smoothing = 0;
    double detail = 1.0;
    bool operator==(const StaticKey&) const = default;
  };

  bool update_static(aq::Context& ctx) {
    StaticKey key{ctx.param_enum(kPreset), ctx.param_string(kPath), ctx.param_int(kSeed),
                  ctx.param_int(kSmoothing), ctx.render_scale()};
    if (built_ && key == static_key_) return true;
    scene::Preset preset;
    if (key.preset == kPresetFile) {
      std::string error = scene::load_model_file(key.path, &preset, ctx, textures_);
      if (!error.empty()) {
        ctx.fail(std::string("scene '") + ctx.node_id() + "', parameter 'path': " + error);
        return false;
      }
    } else if (key.preset == 0) {
      preset = scene::make_underwater(static_cast<uint64_t>(key.seed), key.detail);
    } else if (key.preset > 0 && key.preset < kPresetFile) {
      scene::make_test_preset(kPresetNames[key.preset], &preset);
    } else {
      ctx.fail(std::string("scene '") + ctx.node_id() + "': unknown preset index " +
               std::to_string(key.preset));
      return false;
    }
    static_meshes_.clear();
    for (scene::MeshData& mesh : preset.static_meshes) {
      smooth(mesh, static_cast<int>(key.smoothing));
      static_meshes_.push_back({std::move(mesh), new_geometry_revision()});
    }
    // The static meshes' world bounds, once: every frame's scene bounds start from them.
    static_bounds_min_ = glm::vec3(1e30f);
    static_bounds_max_ = glm::vec3(-1e30f);
    for (const PublishedMesh& mesh : static_meshes_) {
      for (uint32_t v = 0; v < mesh.data.vertex_count(); ++v) {
        glm::vec3 p = glm::vec3(mesh.data.model * glm::vec4(mesh.data.position(v), 1.0f));
        static_bounds_min_ = glm::min(static_bounds_min_, p);
        static_bounds_max_ = glm::max(static_bounds_max_, p);
      }
    }
    animated_objects_ = std::move(preset.animated);
    animated_meshes_.assign(animated_objects_.size(), PublishedMesh{});
    animated_valid_ = false;
    static_key_ = key;
    built_ = true;
    return true;
  }

  void update_animated(aq::Context& ctx) {
    scene::AnimationSettings settings{ctx.param_float(kFishSpeed), ctx.param_float(kSway)};
    int smoothing = static_cast<int>(ctx.param_int(kSmoothing));
    if (animated_valid_ && ctx.time() == animated_time_ &&
        settings.fish_speed == animated_settings_.fish_speed &&
        settings.sway == animated_settings_.sway) {
      return;
    }
    for (size_t i = 0; i < animated_objects_.size(); ++i) {
      scene::MeshData mesh;
      animated_objects_[i].build(ctx.time(), settings, mesh);
      mesh.object_id = animated_objects_[i].object_id;
      smooth(mesh, smoothing);
      animated_meshes_[i] = {std::move(mesh), new_geometry_revision()};
    }
    animated_time_ = ctx.time();
    animated_settings_ = settings;
    animated_valid_ = true;
  }

  static aq_mesh_surface surface_of(const PublishedMesh& mesh) {
    aq_mesh_surface surface{};
    const scene::MeshData& data = mesh.data;
    if (data.texture && data.uvs.size() == 2 * static_cast<size_t>(data.vertex_count())) {
      surface.uvs = data.uvs.data();
      surface.base_color = aq_texture{data.texture->rgba.data(), data.texture->width,
                                      data.texture->height, data.texture->revision};
      surface.alpha_cutoff = 0.5f;
    }
    return surface;
  }

  static aq_mesh describe(const PublishedMesh& mesh) {
    aq_mesh out{};
    out.positions = mesh.data.positions.data();
    out.normals = mesh.data.normals.data();
    out.colors = mesh.data.colors.data();
    out.indices = mesh.data.indices.data();
    out.vertex_count = mesh.data.vertex_count();
    out.index_count = static_cast<uint32_t>(mesh.data.indices.size());
    std::memcpy(out.model, glm::value_ptr(mesh.data.model), sizeof(out.model));
    out.object_id = mesh.data.object_id;
    out.geometry_revision = mesh.revision;
    return out;
  }

  void publish(aq::Context& ctx) {
    meshes_.clear();
    glm::vec3 lo = static_bounds_min_, hi = static_bounds_max_;
    surfaces_.clear();
    for (const PublishedMesh& mesh : static_meshes_) {
      meshes_.push_back(describe(mesh));
      surfaces_.push_back(surface_of(mesh));
    }
    // Animated objects contribute their whole range of motion, so the bounds (and the
    // shadow map fitted to them) stay put while the fish swims.
    for (size_t i = 0; i < animated_meshes_.size(); ++i) {
      meshes_.push_back(describe(animated_meshes_[i]));
      surfaces_.push_back(surface_of(animated_meshes_[i]));
      lo = glm::min(lo, animated_objects_[i].bounds_min);
      hi = glm::max(hi, animated_objects_[i].bounds_max);
    }
    if (meshes_.empty()) lo = hi = glm::vec3(0.0f);

    scene_ = aq_scene{};
    scene_.struct_size = sizeof(aq_scene);
    scene_.meshes = meshes_.data();
    scene_.mesh_count = static_cast<uint32_t>(meshes_.size());
    scene_.surfaces = surfaces_.data();
    scene_.surface_struct_size = sizeof(aq_mesh_surface);
    scene::set_camera_and_light(
        {ctx.param_vec3(kCameraPosition), ctx.param_vec3(kCameraTarget), ctx.param_float(kFov),
         ctx.param_vec3(kLightDirection), ctx.param_vec3(kLightColor),
         ctx.param_float(kLightIntensity), ctx.param_vec3(kAmbient)},
        &scene_);
    for (int k = 0; k < 3; ++k) {
      scene_.bounds_min[k] = lo[k];
      scene_.bounds_max[k] = hi[k];
    }
    scene_.time = ctx.time();
    scene_.water_height = static_cast<float>(ctx.param_float(kWaterHeight));
    scene_.caustic_tile = static_cast<float>(ctx.param_float(kCausticTile));
  }

  bool built_ = false;
  StaticKey static_key_;
  std::vector<PublishedMesh> static_meshes_;
  glm::vec3 static_bounds_min_{1e30f}, static_bounds_max_{-1e30f};
  std::vector<scene::AnimatedObject> animated_objects_;
  std::vector<PublishedMesh> animated_meshes_;
  bool animated_valid_ = false;
  double animated_time_ = 0.0;
  scene::AnimationSettings animated_settings_;
  std::vector<aq_mesh> meshes_;
  std::vector<aq_mesh_surface> surfaces_;
  scene::TextureCache textures_;
  aq_scene scene_{};
};

AQ_SOURCE_NODE(kSceneNode, SceneNode, "scene", "Scene",
               "Procedural underwater scene (seeded), test scenes or a file "
               "(OBJ/glTF), with load-time normal smoothing, camera and light.",
               AQ_NODE_TIME_DEPENDENT, kOutputs, kParams);

}  // namespace

// The object and scene_join nodes (object.cpp, join.cpp) share this plugin.
const aq_node_desc* object_node_desc();
const aq_node_desc* join_node_desc();

AQ_PLUGIN("scene", "1.0", &kSceneNode, object_node_desc(), join_node_desc())
