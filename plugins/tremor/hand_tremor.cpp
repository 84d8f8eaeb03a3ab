// hand_tremor: the geometry half of seed 002's hand tremor. Vertices of objects whose art
// direction asks for a tremor move along their normals by a travelling sine wave of their
// object-space position, scaled by the grazing angle, so silhouettes wobble and faces seen head-on
// stay put (Gilbert, after Montesdeoca et al.):
//
//   scene ──► per mesh: amount = tremor (object) · amplitude, f = tremor_frequency (object)
//     g = 1 − |n_world · v|  (v towards the camera; from the vertex's world position)
//     w = sin(2π f (x + 0.71 y) + ω t) · cos(2π f (0.83 z − 0.57 y) + 1.3 ω t)
//     p' = p + n · amount · ramp(g) · w  (object space; normals kept)
//     ramp(g) = g · clamp((g − head_on) / head_on, 0, 1)   (g itself from 2·head_on on)
//   ──► scene (meshes with amount 0 are handed on untouched: same data, same revision)
//
// A trembling mesh is handed on as two (trembling_mesh.h): its triangles seen head-on, which do
// not move (same revision from frame to frame, so the renderers keep them in their cached layers
// and redraw only the silhouettes), and the others, subdivided until an edge is at most
// 1 / (segments · f) object units, so a coarse mesh's silhouette waves (seed 002's note: tremor
// needs dense geometry) instead of its faces tilting.
//
// A smooth function of time: the wobble is coherent from frame to frame. amplitude 0 hands the
// input scene on as it is, so the g-buffer renders bit-exact what it would without this node.
#include <aquarelle/plugin.hpp>

#include <glm/glm.hpp>

#include <algorithm>
#include <cstring>
#include <string>
#include <vector>

#include "trembling_mesh.h"

namespace {

constexpr aq_port_desc kInputs[] = {aq::scene_port("scene", "objects with their art direction")};
constexpr aq_port_desc kOutputs[] = {aq::scene_port("scene", "the scene with trembling outlines")};
enum Param : uint32_t { kAmplitude, kSpeed, kHeadOn, kSegments };
constexpr aq_param_desc kParams[] = {
    aq::float_param("amplitude", 1.0, 0.0, 10.0,
                    "multiplies each object's `tremor` (world units); 0 hands the scene on as is"),
    aq::float_param("speed", 2.0, 0.0, 100.0, "angular speed of the travelling wave (rad/s)"),
    aq::float_param("head_on", 0.2, 0.0, 0.49,
                    "grazing (1 - |N.V|) at or below which a surface stays put; from twice it on "
                    "the push is as without it, a ramp between. Triangles seen head-on are handed "
                    "on unchanged, so only the silhouettes are redrawn each frame; 0: all move"),
    aq::int_param("segments", 8, 0, 64,
                  "vertices per wavelength (1 / tremor_frequency) along an edge: trembling "
                  "triangles are subdivided to that, so coarse meshes wave; 0: the mesh's own "
                  "vertices only")};

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
    aq::tremor::TremblePlan plan;
    plan.eye = glm::vec3(in->camera.position[0], in->camera.position[1], in->camera.position[2]);
    plan.head_on = ctx.param_float(kHeadOn);
    plan.segments = static_cast<int>(ctx.param_int(kSegments));
    const double phase = ctx.param_float(kSpeed) * ctx.time();
    meshes_.clear();
    surfaces_.clear();
    parts_.resize(in->mesh_count);
    for (uint32_t i = 0; i < in->mesh_count; ++i) {
      const aq_mesh& mesh = in->meshes[i];
      const aq_mesh_surface surface = aq::copy_surface(*in, i);
      const aq::ArtDirection art = aq::surface_art(*in, i);
      const double amount = art.tremor * amplitude;
      if (!(amount > 0.0) || mesh.positions == nullptr || mesh.normals == nullptr) {
        add(mesh, surface);
        continue;
      }
      plan.frequency = art.tremor_frequency;
      aq::tremor::TremblingMesh& part = parts_[i];
      part.prepare(mesh, surface.uvs, plan);
      if (!part.has_moving()) {
        add(mesh, surface);  // seen head-on everywhere: nothing moves, same revision
        continue;
      }
      if (part.has_head_on()) add(part.head_on_part(mesh), surface);
      part.displace(amount, phase);
      aq_mesh_surface moving_surface = surface;
      moving_surface.uvs = part.moving_uvs();
      add(part.moving_part(mesh), moving_surface);
    }
    scene_.meshes = meshes_.data();
    scene_.mesh_count = static_cast<uint32_t>(meshes_.size());
    scene_.surfaces = in->surfaces != nullptr ? surfaces_.data() : nullptr;
    scene_.surface_struct_size = sizeof(aq_mesh_surface);
    return ctx.output_scene(0, &scene_) ? AQ_OK : AQ_ERROR;
  }

 private:
  void add(const aq_mesh& mesh, const aq_mesh_surface& surface) {
    meshes_.push_back(mesh);
    surfaces_.push_back(surface);
  }

  aq_scene scene_{};
  std::vector<aq_mesh> meshes_;
  std::vector<aq_mesh_surface> surfaces_;
  std::vector<aq::tremor::TremblingMesh> parts_;
};

}  // namespace

AQ_NODE(kHandTremorNode, HandTremor, "hand_tremor", "Scene",
        "Geometry hand tremor (seed 002): vertices pushed along their normals by a travelling "
        "sine of their position, scaled by the grazing angle and each object's `tremor`.",
        AQ_NODE_TIME_DEPENDENT, kInputs, kOutputs, kParams);

const aq_node_desc* hand_tremor_node_desc() {
  return &kHandTremorNode;
}
