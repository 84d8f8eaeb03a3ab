// hand_tremor: the geometry half of seed 002's hand tremor. Vertices of objects whose art
// direction asks for a tremor move along their normals by a travelling sine wave of their
// object-space position, scaled by the grazing angle, so silhouettes wobble and faces seen head-on
// stay put (Gilbert, after Montesdeoca et al.):
//
//   scene ──► per mesh: amount = tremor (object) · amplitude, f = tremor_frequency (object)
//     g = 1 − |n_world · v|  (v towards the camera; from the vertex's world position)
//     w = sin(2π f (x + 0.71 y) + ω t) · cos(2π f (0.83 z − 0.57 y) + 1.3 ω t)
//     p' = p + n · amount · g · w        (object space; normals kept)
//   ──► scene (meshes with amount 0 are handed on untouched: same data, same revision)
//
// A smooth function of time: the wobble is coherent from frame to frame. amplitude 0 hands the
// input scene on as it is, so the g-buffer renders bit-exact what it would without this node.
#include <aquarelle/plugin.hpp>

#include <glm/glm.hpp>
#include <glm/gtc/type_ptr.hpp>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstring>
#include <string>
#include <vector>

namespace {

constexpr aq_port_desc kInputs[] = {aq::scene_port("scene", "objects with their art direction")};
constexpr aq_port_desc kOutputs[] = {aq::scene_port("scene", "the scene with trembling outlines")};
enum Param : uint32_t { kAmplitude, kSpeed };
constexpr aq_param_desc kParams[] = {
    aq::float_param("amplitude", 1.0, 0.0, 10.0,
                    "multiplies each object's `tremor` (world units); 0 hands the scene on as is"),
    aq::float_param("speed", 2.0, 0.0, 100.0, "angular speed of the travelling wave (rad/s)")};

constexpr double kTwoPi = 6.283185307179586;

// Revisions of the meshes this plugin makes: a range of its own, so they never meet the scene
// plugin's counter (which starts at 1) within a process.
uint64_t new_revision() {
  static std::atomic<uint64_t> next{uint64_t{1} << 62};
  return next.fetch_add(1);
}

struct Trembled {
  std::vector<float> positions;
};

class HandTremor {
 public:
  int process(aq::Context& ctx) {
    const aq_scene* in = ctx.input_scene(0);
    if (in == nullptr) {
      return ctx.fail(std::string("hand_tremor '") + ctx.node_id() +
                      "': input `scene` is not connected; connect a scene_join's `scene`");
    }
    const double amplitude = ctx.param_float(kAmplitude);
    // A producer built against an older plugin.h has a shorter aq_scene: copy what it has.
    scene_ = aq_scene{};
    std::memcpy(&scene_, in, std::min<size_t>(in->struct_size, sizeof(aq_scene)));
    scene_.struct_size = sizeof(aq_scene);
    if (!(amplitude > 0.0)) return ctx.output_scene(0, in) ? AQ_OK : AQ_ERROR;
    meshes_.assign(in->meshes, in->meshes + in->mesh_count);
    parts_.resize(in->mesh_count);
    const glm::vec3 eye(in->camera.position[0], in->camera.position[1], in->camera.position[2]);
    const double phase = ctx.param_float(kSpeed) * ctx.time();
    for (uint32_t i = 0; i < in->mesh_count; ++i) {
      const aq::ArtDirection art = aq::surface_art(*in, i);
      const double amount = art.tremor * amplitude;
      aq_mesh& mesh = meshes_[i];
      if (!(amount > 0.0) || mesh.positions == nullptr || mesh.normals == nullptr) continue;
      tremble(mesh, amount, art.tremor_frequency, phase, eye, &parts_[i]);
      mesh.positions = parts_[i].positions.data();
      mesh.geometry_revision = new_revision();
    }
    scene_.meshes = meshes_.data();
    return ctx.output_scene(0, &scene_) ? AQ_OK : AQ_ERROR;
  }

 private:
  static void tremble(const aq_mesh& mesh, double amount, double frequency, double phase,
                      const glm::vec3& eye, Trembled* out) {
    const glm::mat4 model = glm::make_mat4(mesh.model);
    const glm::mat3 normal_matrix = glm::transpose(glm::inverse(glm::mat3(model)));
    out->positions.assign(mesh.positions, mesh.positions + 3 * size_t{mesh.vertex_count});
    for (uint32_t v = 0; v < mesh.vertex_count; ++v) {
      const glm::vec3 p(mesh.positions[3 * v], mesh.positions[3 * v + 1],
                        mesh.positions[3 * v + 2]);
      const glm::vec3 n(mesh.normals[3 * v], mesh.normals[3 * v + 1], mesh.normals[3 * v + 2]);
      const glm::vec3 world = glm::vec3(model * glm::vec4(p, 1.0f));
      const glm::vec3 world_normal = normal_matrix * n;
      const glm::vec3 to_eye = eye - world;
      const float ln = glm::length(world_normal), le = glm::length(to_eye);
      if (!(ln > 1e-12f) || !(le > 1e-12f)) continue;
      const double grazing = 1.0 - std::abs(glm::dot(world_normal / ln, to_eye / le));
      const double w = std::sin(kTwoPi * frequency * (p.x + 0.71 * p.y) + phase) *
                       std::cos(kTwoPi * frequency * (0.83 * p.z - 0.57 * p.y) + 1.3 * phase);
      const double push = amount * grazing * w;
      if (!std::isfinite(push)) continue;
      for (int k = 0; k < 3; ++k) {
        out->positions[3 * v + k] = static_cast<float>(p[k] + n[k] * push);
      }
    }
  }

  aq_scene scene_{};
  std::vector<aq_mesh> meshes_;
  std::vector<Trembled> parts_;
};

}  // namespace

AQ_NODE(kHandTremorNode, HandTremor, "hand_tremor", "Scene",
        "Geometry hand tremor (seed 002): vertices pushed along their normals by a travelling "
        "sine of their position, scaled by the grazing angle and each object's `tremor`.",
        AQ_NODE_TIME_DEPENDENT, kInputs, kOutputs, kParams);

const aq_node_desc* hand_tremor_node_desc() {
  return &kHandTremorNode;
}
