// A model file as the object and scene nodes use it: meshes in their own space, the node
// hierarchy that places them, materials (base colour, base colour texture), keyframe
// animation, and the unit/up-axis correction the file's metadata asks for. Loaded once per
// path (model_loader.cpp); instances(time) gives where every mesh is at a time.
//
//   file ──Assimp──► meshes (object space, Kd/baseColor x vertex colours, uvs)
//                    materials ─► texture file beside the model, or an embedded one
//                    nodes + channels ─► instances(time): (mesh, model matrix) pairs
//                    metadata (UnitScaleFactor, UpAxis) ─► root_correction
#pragma once

#include "mesh_data.h"

#include <glm/glm.hpp>
#include <glm/gtc/quaternion.hpp>

#include <map>
#include <string>
#include <vector>

namespace scene {

struct ModelMaterial {
  std::string name;
  glm::vec3 color{0.8f};  // Kd or baseColorFactor (linear)
  // Where the base colour texture is: a file path (resolved beside the model), or the key of
  // an embedded texture ("*0"); empty when the material has none or its file is missing.
  std::string texture;
  bool embedded = false;
};

struct ModelMesh {
  MeshData data;  // object space; colours already hold the material colour
  uint32_t material = 0;
};

struct ModelNode {
  std::string name;
  int parent = -1;  // parents come before their children
  glm::mat4 local{1.0f};
  std::vector<uint32_t> meshes;
  int channel = -1;  // index into Model::channels, -1 when not animated
};

template <typename T>
struct Key {
  double time;  // seconds
  T value;
};

struct NodeChannel {
  std::vector<Key<glm::vec3>> positions;
  std::vector<Key<glm::quat>> rotations;
  std::vector<Key<glm::vec3>> scales;
};

struct EmbeddedTexture {
  std::vector<unsigned char> bytes;  // the encoded file (PNG, JPEG...)
  std::string extension;             // "png"
};

struct Model {
  std::string path;
  std::vector<ModelMesh> meshes;
  std::vector<ModelMaterial> materials;
  std::vector<ModelNode> nodes;
  std::vector<NodeChannel> channels;
  double duration = 0.0;            // seconds of the first animation; 0 when the file has none
  glm::mat4 root_correction{1.0f};  // file units to metres, file up axis to +y
  std::string correction;           // what root_correction does, for messages ("" if nothing)
  std::map<std::string, EmbeddedTexture> embedded;
  // What was missing and what is used instead (a material file, a texture).
  std::vector<std::string> warnings;
};

// Reads the file. Returns "" or what failed (and how to fix it).
std::string load_model(const std::string& path, Model* model);

struct Instance {
  uint32_t mesh;
  glm::mat4 transform;  // mesh space to model space (root correction included)
};
// Every placed mesh at `time` seconds (animation loops over its duration).
std::vector<Instance> model_instances(const Model& model, double time);

// Problems `aquarelle validate` reports for a model file without reading any image: errors
// (not a mesh, no triangles) and warnings (missing material file or texture).
void check_model_file(const std::string& path, std::vector<std::string>* errors,
                      std::vector<std::string>* warnings);

}  // namespace scene
