// object: one placed thing of a scene, from a model file (anything Assimp reads, with its
// materials, textures and keyframes) or a procedural shape, as a scene fragment that
// `scene_join` gathers with the others, a camera and a light.
//
//   path / source ──► Model (meshes, materials, nodes, keyframes), loaded once per file
//   textures ───────► TextureCache (host: OpenImageIO + OpenColorIO), once per file
//   time ──► keyframes (animation: file) or a swim loop with a travelling body wave (swim)
//   fit ──► the model's time-0 bounds scaled into a unit box resting on y = 0
//   position, rotation (degrees, x then y then z), scale ──► model matrix
//   ──► aq_scene fragment: meshes + surfaces (uvs, texture, cut-out), world bounds; its camera
//       and light are unused (scene_join sets them)
//
// Per-object settings later nodes read (an object's colour override today; the art-direction
// amounts of seed 002 next) live here, next to the id that tags its g-buffer pixels.
#include <aquarelle/plugin.hpp>
#include <aquarelle/sdk/mesh_smoothing.hpp>

#include "model.h"
#include "object_shapes.h"
#include "revision.h"
#include "terrain.h"
#include "textures.h"

#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/type_ptr.hpp>

#include <cmath>
#include <cstring>
#include <iterator>
#include <string>
#include <vector>

namespace {

constexpr aq_port_desc kOutputs[] = {aq::scene_port(
    "object", "a scene fragment: this object's meshes, placed, with their surfaces and bounds")};

enum Param {
  kSource,
  kPath,
  kTexture,
  kPosition,
  kRotation,
  kScale,
  kFit,
  kId,
  kColorOverride,
  kColor,
  kAlphaCutoff,
  kSmoothing,
  kAnimation,
  kSwimRadius,
  kSwimSpeed,
  kSwimWave,
  kSeed,
  kSwimPhase,
  kBleed,  // art direction (seed 002), carried on each surface for control_map and tremor
  kEdgeDarkening,
  kTremor,
  kTremorFrequency,
  kFbmDensity,
  kFbmScale,
  kSpin,
  kSwimForward,
  kTerrainSwell,
  kTerrainSwellFrequency,
  kTerrainBumps,
  kTerrainBumpsFrequency,
  kTerrainCliff,
  kTerrainCells
};
enum Animation { kAnimationNone, kAnimationFile, kAnimationSwim, kAnimationSpin };
enum Forward { kForwardPlusX, kForwardMinusX, kForwardPlusZ, kForwardMinusZ };

constexpr aq_param_desc kParams[] = {
    aq::enum_param("source",
                   "file|cube|sphere|plane|card|pot|rock|coral|shell|starfish|fish|terrain", 0,
                   "`file` loads `path`; the others are procedural shapes"),
    aq::path_param("path", "model file (OBJ+MTL, glTF/GLB, FBX, PLY... anything Assimp reads)"),
    aq::path_param("texture",
                   "base colour image for a procedural shape (a card's alpha cuts it out); "
                   "files use their materials' textures"),
    aq::vec3_param("position", 0, 0, 0, -1000, 1000, "where the object's origin goes (world)"),
    aq::vec3_param("rotation", 0, 0, 0, -360, 360,
                   "rotation in degrees about x, then y, then z (world axes)"),
    aq::vec3_param("scale", 1, 1, 1, -1000, 1000, "scale along the object's own axes"),
    aq::bool_param("fit", false,
                   "scale and move the object so it fits a unit box resting on y = 0, centred "
                   "on x and z, before position/rotation/scale"),
    aq::int_param("id", 1, 1, 65535, "object id in the g-buffer (>= 1; 0 is the background)"),
    aq::bool_param("color_override", false, "replace the object's colours by `color`"),
    aq::color_param("color", 0.8, 0.8, 0.8,
                    "the colour when color_override is on (textures still multiply it)"),
    aq::float_param("alpha_cutoff", 0.5, 0.0, 1.0,
                    "texture alpha below this is a hole (cut-out cards); 0 keeps every pixel"),
    aq::int_param("smoothing", 0, 0, 64,
                  "normal smoothing iterations at load time (7: the seed's soft look)"),
    aq::enum_param(
        "animation", "none|file|swim|spin", 1,
        "`file` plays the file's keyframes (looped), `swim` swims a loop around "
        "`position` with a body wave travelling to the tail (`swim_forward`: +x), `spin` "
        "turns the object about `position` by `spin` (windmill sails)"),
    aq::float_param("swim_radius", 2.0, 0.0, 100.0, "radius of the swim loop (world units)"),
    aq::float_param("swim_speed", 0.35, -5.0, 5.0, "swim loop speed, radians per second"),
    aq::float_param("swim_wave", 0.056, 0.0, 0.5,
                    "body wave amplitude as a fraction of the body length (0 glides)"),
    aq::int_param("seed", 7, 0, 2147483647, "seed of the rock and coral shapes"),
    aq::float_param("swim_phase", 0.0, -360.0, 360.0,
                    "where on the swim loop the object is at time 0, degrees (0: +x of "
                    "`position`, 90: +z)",
                    0.0, "angle"),
    aq::float_param("bleed", 0.0, 0.0, 1.0,
                    "art direction: how much the object's colour bleeds (control map red)"),
    aq::float_param("edge_darkening", 1.0, 0.0, 4.0,
                    "art direction: edge darkening amount (control map green)"),
    aq::float_param("tremor", 0.0, 0.0, 1.0,
                    "art direction: hand tremor amplitude in world units (control map alpha)"),
    aq::float_param("tremor_frequency", 4.0, 0.0, 100.0,
                    "art direction: hand tremor waves per world unit"),
    aq::float_param("fbm_density", 0.0, 0.0, 1.0,
                    "art direction: 0 keeps the amounts constant over the object, 1 modulates "
                    "them fully by object-space FBM"),
    aq::float_param("fbm_scale", 2.0, 0.01, 100.0,
                    "art direction: FBM lattice cells per object-space unit"),
    aq::vec3_param("spin", 0, 0, 90, -36000, 36000,
                   "animation `spin`: degrees per second about world x, y and z through "
                   "`position`"),
    aq::enum_param("swim_forward", "+x|-x|+z|-z", kForwardPlusX,
                   "animation `swim`: the model's own axis that points forward (its nose): "
                   "the loop turns it along the direction of travel and the body wave runs "
                   "from it to the tail, sideways across it"),
    aq::float_param("terrain_swell", 0.08, -10.0, 10.0,
                    "source `terrain`: amplitude of the large swells (object units; the unit "
                    "square is the floor)"),
    aq::float_param("terrain_swell_frequency", 3.0, 0.0, 1000.0,
                    "source `terrain`: swell noise cells per object unit"),
    aq::float_param("terrain_bumps", 0.012, -10.0, 10.0,
                    "source `terrain`: amplitude of the small bumps (object units)"),
    aq::float_param("terrain_bumps_frequency", 24.0, 0.0, 1000.0,
                    "source `terrain`: bump noise cells per object unit"),
    aq::float_param("terrain_cliff", 0.0, -10.0, 10.0,
                    "source `terrain`: height of a rock cliff rising along the back (-z) edge "
                    "(0: none)"),
    aq::int_param("terrain_cells", 128, 1, 1024,
                  "source `terrain`: grid cells per side (2 triangles each); the heights "
                  "between vertices are linear, so finer grids follow the bumps closer")};

constexpr int kSourceFile = 0;
constexpr double kTwoPi = 6.283185307179586;

glm::mat4 placement(const aq::Context& ctx) {
  const double* p = ctx.param_vec3(kPosition);
  const double* r = ctx.param_vec3(kRotation);
  const double* s = ctx.param_vec3(kScale);
  glm::mat4 m = glm::translate(glm::mat4(1.0f), glm::vec3(p[0], p[1], p[2]));
  m = glm::rotate(m, glm::radians(static_cast<float>(r[2])), glm::vec3(0, 0, 1));
  m = glm::rotate(m, glm::radians(static_cast<float>(r[1])), glm::vec3(0, 1, 0));
  m = glm::rotate(m, glm::radians(static_cast<float>(r[0])), glm::vec3(1, 0, 0));
  return glm::scale(m, glm::vec3(s[0], s[1], s[2]));
}

// Where the swim loop puts the object at `time`: on a circle of `radius` around the origin,
// bobbing a little, its +x along the direction of travel (as the procedural fish swims).
glm::mat4 swim_frame(double time, double radius, double speed, double phase_degrees) {
  const float angle = static_cast<float>(speed * time + phase_degrees * kTwoPi / 360.0);
  const float r = static_cast<float>(radius);
  const glm::vec3 at(r * std::cos(angle), 0.12f * r * std::sin(2.0f * angle), r * std::sin(angle));
  const float direction = speed >= 0.0 ? 1.0f : -1.0f;
  const glm::vec3 tangent = direction * glm::vec3(-std::sin(angle), 0.0f, std::cos(angle));
  const float yaw = std::atan2(-tangent.z, tangent.x);
  return glm::rotate(glm::translate(glm::mat4(1.0f), at), yaw, glm::vec3(0, 1, 0));
}

// The spin animation at `time`: rotations about world x, y, z through `centre` (degrees per
// second from the `spin` parameter).
glm::mat4 spin_frame(const aq::Context& ctx, const glm::vec3& centre, double time) {
  const double* rate = ctx.param_vec3(kSpin);
  glm::mat4 m = glm::translate(glm::mat4(1.0f), centre);
  for (int axis = 2; axis >= 0; --axis) {
    glm::vec3 along(0.0f);
    along[axis] = 1.0f;
    m = glm::rotate(m, static_cast<float>(glm::radians(std::fmod(rate[axis] * time, 360.0))),
                    along);
  }
  return glm::translate(m, -centre);
}

// The model's forward axis (swim_forward) as a component of its positions (0: x, 2: z) and a
// sign; the body wave bends along the other horizontal component, towards `side_sign`: the
// model axis that forward_to_x turns onto world +z (+z for +x, -x for +z, -z for -x, +x for
// -z), so a model built along any axis swims exactly as the same model built along +x.
struct ForwardAxis {
  int component = 0;
  float sign = 1.0f;
  float side_sign = 1.0f;
};
ForwardAxis forward_axis(int64_t forward) {
  return {forward == kForwardPlusZ || forward == kForwardMinusZ ? 2 : 0,
          forward == kForwardMinusX || forward == kForwardMinusZ ? -1.0f : 1.0f,
          forward == kForwardMinusX || forward == kForwardPlusZ ? -1.0f : 1.0f};
}

// Turns the model's forward axis onto +x (about y), so the swim loop, which heads +x along
// the direction of travel, heads the model's nose there.
glm::mat4 forward_to_x(int64_t forward) {
  const float degrees = forward == kForwardMinusX   ? 180.0f
                        : forward == kForwardPlusZ  ? 90.0f
                        : forward == kForwardMinusZ ? -90.0f
                                                    : 0.0f;
  return glm::rotate(glm::mat4(1.0f), glm::radians(degrees), glm::vec3(0, 1, 0));
}

// The travelling body wave of a swimming fish on any mesh: sideways offsets growing
// quadratically from the nose (the far end of the forward axis) to the tail, a wave moving
// tailwards.
void body_wave(scene::MeshData& mesh, double time, double amplitude, ForwardAxis axis) {
  const uint32_t n = mesh.vertex_count();
  if (n == 0 || amplitude <= 0.0) return;
  const int along = axis.component, side = 2 - axis.component;
  float lo = 1e30f, hi = -1e30f;
  for (uint32_t v = 0; v < n; ++v) {
    lo = std::min(lo, axis.sign * mesh.positions[3 * v + along]);
    hi = std::max(hi, axis.sign * mesh.positions[3 * v + along]);
  }
  const float length = std::max(hi - lo, 1e-6f);
  for (uint32_t v = 0; v < n; ++v) {
    const float x = axis.sign * mesh.positions[3 * v + along];
    const float s = (hi - x) / length;  // 0 at the nose, 1 at the tail
    const float phase = static_cast<float>(kTwoPi * 1.4 * (x - hi) / length - 8.0 * time);
    mesh.positions[3 * v + side] +=
        axis.side_sign * static_cast<float>(amplitude) * length * s * s * std::sin(phase);
  }
}

// The host stores base colour texels as half floats (RGBA16F), so an alpha of exactly the
// cut-off (e.g. 204/255 = 0.8) arrives as 0.7998 and would test below a float 0.8: the cut-off
// is rounded the same way (to nearest, ties to even). Rounding is monotonic, so every alpha at
// or above the cut-off stays at or above it.
float as_stored_texel(double value) {
  if (!(value > 0.0)) return 0.0f;
  const int exponent = std::max(std::ilogb(value), -14);  // below 2^-14: half's subnormals
  const double spacing = std::ldexp(1.0, exponent - 10);  // 10 fraction bits
  return static_cast<float>(std::nearbyint(value / spacing) * spacing);
}

void box_of(const scene::MeshData& mesh, const glm::mat4& to_world, glm::vec3* lo, glm::vec3* hi) {
  for (uint32_t v = 0; v < mesh.vertex_count(); ++v) {
    const glm::vec3 p = glm::vec3(to_world * glm::vec4(mesh.position(v), 1.0f));
    *lo = glm::min(*lo, p);
    *hi = glm::max(*hi, p);
  }
}

struct Part {
  scene::MeshData data;  // object space, colours final
  uint64_t revision = 0;
  glm::mat4 model{1.0f};
};

class ObjectNode {
 public:
  int process(aq::Context& ctx) {
    if (!update_model(ctx)) return AQ_ERROR;
    update_parts(ctx);
    publish(ctx);
    return ctx.output_scene(0, &fragment_) ? AQ_OK : AQ_ERROR;
  }

 private:
  struct LoadKey {
    int64_t source = -1;
    std::string path, texture;
    int64_t smoothing = 0, seed = 0;
    bool color_override = false;
    double color[3] = {0, 0, 0};
    scene::TerrainShape terrain;
    bool operator==(const LoadKey& o) const {
      const auto same_terrain = [](const scene::TerrainShape& a, const scene::TerrainShape& b) {
        return a.swell == b.swell && a.swell_frequency == b.swell_frequency && a.bumps == b.bumps &&
               a.bumps_frequency == b.bumps_frequency && a.cliff == b.cliff && a.cells == b.cells;
      };
      return source == o.source && path == o.path && texture == o.texture &&
             smoothing == o.smoothing && seed == o.seed && color_override == o.color_override &&
             std::memcmp(color, o.color, sizeof(color)) == 0 && same_terrain(terrain, o.terrain);
    }
  };

  std::string name(const aq::Context& ctx) const {
    return std::string("object '") + ctx.node_id() + "'";
  }

  // Loads the file (or builds the shape at time 0) with final colours and textures.
  bool update_model(aq::Context& ctx) {
    LoadKey key;
    key.source = ctx.param_enum(kSource);
    key.path = ctx.param_string(kPath);
    key.texture = ctx.param_string(kTexture);
    key.smoothing = ctx.param_int(kSmoothing);
    key.seed = ctx.param_int(kSeed);
    key.color_override = ctx.param_bool(kColorOverride);
    std::memcpy(key.color, ctx.param_vec3(kColor), sizeof(key.color));
    key.terrain.swell = ctx.param_float(kTerrainSwell);
    key.terrain.swell_frequency = ctx.param_float(kTerrainSwellFrequency);
    key.terrain.bumps = ctx.param_float(kTerrainBumps);
    key.terrain.bumps_frequency = ctx.param_float(kTerrainBumpsFrequency);
    key.terrain.cliff = ctx.param_float(kTerrainCliff);
    key.terrain.cells = static_cast<int>(ctx.param_int(kTerrainCells));
    if (loaded_ && key == key_) return true;
    model_ = scene::Model{};
    if (key.source == kSourceFile) {
      if (std::string error = scene::load_model(key.path, &model_); !error.empty()) {
        ctx.fail(name(ctx) + ", parameter 'path': " + error);
        return false;
      }
      scene::apply_model_textures(ctx, model_, textures_);
      if (!model_.correction.empty()) {
        ctx.warn(name(ctx) + ": '" + key.path + "': " + model_.correction + " (file metadata)");
      }
    } else {
      constexpr int64_t kShapeCount = static_cast<int64_t>(std::size(scene::kObjectShapes));
      if (key.source < 1 || key.source > kShapeCount) {
        ctx.fail(name(ctx) + ", parameter 'source': unknown source index " +
                 std::to_string(key.source));
        return false;
      }
      scene::ModelMesh mesh;
      shape_ = scene::kObjectShapes[key.source - 1];
      if (shape_ == "terrain") {
        if (std::string problem = scene::terrain_problem(key.terrain); !problem.empty()) {
          ctx.fail(name(ctx) + ": " + problem);
          return false;
        }
        scene::make_terrain(key.terrain, static_cast<uint64_t>(key.seed), mesh.data);
      } else {
        scene::make_object_shape(shape_, 0.0, static_cast<uint64_t>(key.seed), mesh.data);
      }
      model_.path = shape_;
      model_.meshes.push_back(std::move(mesh));
      model_.nodes.push_back(scene::ModelNode{"shape", -1, glm::mat4(1.0f), {0}, -1});
    }
    shape_texture_.reset();
    if (!key.texture.empty()) {
      std::string error;
      shape_texture_ = textures_.file(ctx, key.texture, &error);
      if (!shape_texture_) {
        model_.warnings.push_back("parameter 'texture': " + error + "; using the shape's colours");
      } else if (key.source == kSourceFile) {
        model_.warnings.push_back("parameter 'texture' is for procedural shapes; '" + key.path +
                                  "' uses its materials' textures");
        shape_texture_.reset();
      }
    }
    for (scene::ModelMesh& mesh : model_.meshes) finish_mesh(key, mesh.data);
    for (const std::string& warning : model_.warnings) ctx.warn(name(ctx) + ": " + warning);
    fit_ = fit_transform();
    key_ = key;
    loaded_ = true;
    parts_valid_ = false;
    return true;
  }

  void finish_mesh(const LoadKey& key, scene::MeshData& mesh) const {
    if (key.color_override) {
      for (size_t i = 0; i + 2 < mesh.colors.size(); i += 3) {
        for (int c = 0; c < 3; ++c) mesh.colors[i + c] = static_cast<float>(key.color[c]);
      }
    }
    if (shape_texture_) {
      if (mesh.uvs.empty()) scene::box_project_uvs(mesh);
      mesh.texture = shape_texture_;
    }
    smooth(mesh, static_cast<int>(key.smoothing));
  }

  static void smooth(scene::MeshData& mesh, int iterations) {
    if (iterations <= 0) return;
    aq::mesh::SmoothingOptions options;
    options.iterations = iterations;
    aq::mesh::smooth_normals(mesh.positions, mesh.indices, mesh.normals, options);
  }

  // Unit box, resting on y = 0, centred on x and z, from the bounds at time 0.
  glm::mat4 fit_transform() const {
    glm::vec3 lo(1e30f), hi(-1e30f);
    for (const scene::Instance& instance : scene::model_instances(model_, 0.0)) {
      box_of(model_.meshes[instance.mesh].data, instance.transform, &lo, &hi);
    }
    if (!(hi.x >= lo.x)) return glm::mat4(1.0f);
    const float extent = std::max({hi.x - lo.x, hi.y - lo.y, hi.z - lo.z, 1e-6f});
    const glm::vec3 anchor(0.5f * (lo.x + hi.x), lo.y, 0.5f * (lo.z + hi.z));
    return glm::scale(glm::mat4(1.0f), glm::vec3(1.0f / extent)) *
           glm::translate(glm::mat4(1.0f), -anchor);
  }

  bool wave_animated(const aq::Context& ctx) const {
    const int64_t animation = ctx.param_enum(kAnimation);
    return animation == kAnimationSwim && (ctx.param_float(kSwimWave) > 0.0 || shape_ == "fish");
  }

  // Meshes and their matrices at this frame's time; geometry is rebuilt (a new revision) only
  // when a body wave moves it.
  void update_parts(aq::Context& ctx) {
    const int64_t animation = ctx.param_enum(kAnimation);
    const double time = ctx.time();
    const bool deforming = wave_animated(ctx);
    const glm::mat4 fit = ctx.param_bool(kFit) ? fit_ : glm::mat4(1.0f);
    const glm::mat4 place = placement(ctx) * fit;
    const glm::mat4 swim =
        animation == kAnimationSwim
            ? swim_frame(time, ctx.param_float(kSwimRadius), ctx.param_float(kSwimSpeed),
                         ctx.param_float(kSwimPhase))
            : glm::mat4(1.0f);
    const double instance_time = animation == kAnimationFile ? time : 0.0;
    const std::vector<scene::Instance> instances = scene::model_instances(model_, instance_time);
    if (!parts_valid_ || deforming || instances.size() != parts_.size()) {
      parts_.clear();
      for (const scene::Instance& instance : instances) {
        Part part;
        part.data = model_.meshes[instance.mesh].data;
        if (deforming) deform(ctx, part.data, time);
        part.revision = scene::new_revision();
        parts_.push_back(std::move(part));
      }
      parts_valid_ = !deforming;
    }
    // The swim loop goes around `position`, the object turned and scaled in its own frame, its
    // forward axis first turned onto +x (after `fit`, which centres it: the turn keeps that).
    glm::mat4 world = animation == kAnimationSwim
                          ? glm::translate(glm::mat4(1.0f), glm::vec3(place[3])) * swim *
                                glm::translate(glm::mat4(1.0f), -glm::vec3(place[3])) *
                                placement(ctx) * forward_to_x(ctx.param_enum(kSwimForward)) * fit
                          : place;
    if (animation == kAnimationSpin) world = spin_frame(ctx, glm::vec3(place[3]), time) * place;
    for (size_t i = 0; i < parts_.size(); ++i) {
      parts_[i].model = world * instances[i].transform;
      parts_[i].data.object_id = static_cast<uint32_t>(ctx.param_int(kId));
    }
  }

  void deform(const aq::Context& ctx, scene::MeshData& mesh, double time) const {
    if (shape_ == "fish") {  // the procedural fish has its own body wave
      scene::MeshData moving;
      scene::make_object_shape("fish", time, 0, moving);
      std::swap(mesh.positions, moving.positions);
      std::swap(mesh.normals, moving.normals);
      smooth(mesh, static_cast<int>(key_.smoothing));
      return;
    }
    body_wave(mesh, time, ctx.param_float(kSwimWave), forward_axis(ctx.param_enum(kSwimForward)));
  }

  void publish(aq::Context& ctx) {
    meshes_.clear();
    surfaces_.clear();
    glm::vec3 lo(1e30f), hi(-1e30f);
    const float cutoff = as_stored_texel(ctx.param_float(kAlphaCutoff));
    for (const Part& part : parts_) {
      aq_mesh mesh{};
      mesh.positions = part.data.positions.data();
      mesh.normals = part.data.normals.data();
      mesh.colors = part.data.colors.data();
      mesh.indices = part.data.indices.data();
      mesh.vertex_count = part.data.vertex_count();
      mesh.index_count = static_cast<uint32_t>(part.data.indices.size());
      std::memcpy(mesh.model, glm::value_ptr(part.model), sizeof(mesh.model));
      mesh.object_id = part.data.object_id;
      mesh.geometry_revision = part.revision;
      meshes_.push_back(mesh);
      aq_mesh_surface surface{};
      const bool textured = part.data.texture && part.data.uvs.size() == 2 * mesh.vertex_count;
      surface.uvs = textured ? part.data.uvs.data() : nullptr;
      if (textured) {
        surface.base_color = aq_texture{part.data.texture->rgba.data(), part.data.texture->width,
                                        part.data.texture->height, part.data.texture->revision};
        surface.alpha_cutoff = cutoff;
      }
      surface.art_set = 1;
      surface.bleed = static_cast<float>(ctx.param_float(kBleed));
      surface.edge_darkening = static_cast<float>(ctx.param_float(kEdgeDarkening));
      surface.tremor = static_cast<float>(ctx.param_float(kTremor));
      surface.tremor_frequency = static_cast<float>(ctx.param_float(kTremorFrequency));
      surface.fbm_density = static_cast<float>(ctx.param_float(kFbmDensity));
      surface.fbm_scale = static_cast<float>(ctx.param_float(kFbmScale));
      surfaces_.push_back(surface);
      box_of(part.data, part.model, &lo, &hi);
    }
    if (ctx.param_enum(kAnimation) == kAnimationSwim) swim_bounds(ctx, &lo, &hi);
    if (meshes_.empty()) lo = hi = glm::vec3(0.0f);
    fragment_ = aq_scene{};
    fragment_.struct_size = sizeof(aq_scene);
    fragment_.meshes = meshes_.data();
    fragment_.mesh_count = static_cast<uint32_t>(meshes_.size());
    fragment_.surfaces = surfaces_.data();
    fragment_.surface_struct_size = sizeof(aq_mesh_surface);
    for (int k = 0; k < 3; ++k) {
      fragment_.bounds_min[k] = lo[k];
      fragment_.bounds_max[k] = hi[k];
    }
    fragment_.time = ctx.time();
  }

  // A swimming object's bounds hold its whole loop, so a scene's bounds (and the shadow map
  // fitted to them) stay put while it swims.
  void swim_bounds(const aq::Context& ctx, glm::vec3* lo, glm::vec3* hi) const {
    const glm::vec3 centre = glm::vec3(placement(ctx)[3]);
    const glm::vec3 size = *hi - *lo;
    const float reach = static_cast<float>(ctx.param_float(kSwimRadius)) +
                        0.5f * std::max({size.x, size.y, size.z});
    const float bob = 0.12f * static_cast<float>(ctx.param_float(kSwimRadius)) + 0.5f * size.y;
    *lo = glm::min(*lo, centre - glm::vec3(reach, bob, reach));
    *hi = glm::max(*hi, centre + glm::vec3(reach, bob, reach));
  }

  bool loaded_ = false;
  LoadKey key_;
  scene::Model model_;
  std::string shape_;
  scene::TextureCache textures_;
  std::shared_ptr<const scene::Texture> shape_texture_;
  glm::mat4 fit_{1.0f};
  std::vector<Part> parts_;
  bool parts_valid_ = false;
  std::vector<aq_mesh> meshes_;
  std::vector<aq_mesh_surface> surfaces_;
  aq_scene fragment_{};
};

// `aquarelle validate`: the model file must be a mesh; missing material files and textures
// are warnings (the render uses the material colour).
void check_object(const aq_param_value* params, uint32_t count,
                  void (*report)(void*, int, uint32_t, const char*), void* data) {
  if (count <= kPath || params[kSource].i != kSourceFile) return;
  const std::string path = params[kPath].s != nullptr ? params[kPath].s : "";
  if (path.empty()) {
    report(data, 0, kPath, "no model file: set `path` (or choose a procedural `source`)");
    return;
  }
  std::vector<std::string> errors, warnings;
  scene::check_model_file(path, &errors, &warnings);
  for (const std::string& error : errors) report(data, 0, kPath, error.c_str());
  for (const std::string& warning : warnings) report(data, 1, kPath, warning.c_str());
}

}  // namespace

AQ_SOURCE_NODE_CHECKED(kObjectNode, ObjectNode, "object", "Scene",
                       "One object of a scene: a model file (OBJ/MTL, glTF, FBX...) with its "
                       "textures and keyframes, or a procedural shape; placed, coloured, "
                       "optionally swimming. Join objects with scene_join.",
                       AQ_NODE_TIME_DEPENDENT, kOutputs, kParams, &check_object);

const aq_node_desc* object_node_desc() {
  return &kObjectNode;
}
