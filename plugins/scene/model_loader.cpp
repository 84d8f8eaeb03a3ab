// Loads a model file (OBJ, glTF/GLB, FBX... whatever Assimp reads) into a Model: meshes in
// their own space (triangulated, flat normals where the file has none; smoothing happens
// later, like for procedural meshes), colours from the material's base colour (glTF) or
// diffuse colour (OBJ's Kd) times vertex colours, uvs, the base colour texture each material
// names (OBJ map_Kd, glTF baseColorTexture, beside the file or embedded), the node hierarchy
// and its keyframes, and the unit/up-axis correction from the file's metadata.
// load_model_file keeps the `scene` node's `preset: file` (every mesh placed at time 0).
#include "mesh_file_checks.h"
#include "mesh_import.h"
#include "model.h"
#include "presets.h"
#include "textures.h"

#include <assimp/material.h>
#include <assimp/metadata.h>
#include <assimp/postprocess.h>
#include <assimp/scene.h>
#include <assimp/Importer.hpp>

#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/type_ptr.hpp>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

namespace scene {

namespace {

namespace fs = std::filesystem;

constexpr unsigned kImportFlags = aiProcess_Triangulate | aiProcess_GenNormals |
                                  aiProcess_SortByPType | aiProcess_FindInvalidData;

glm::vec3 material_color(const aiMaterial* material) {
  aiColor4D color(0.8f, 0.8f, 0.8f, 1.0f);
  if (material == nullptr) return {color.r, color.g, color.b};
  if (material->Get(AI_MATKEY_BASE_COLOR, color) != AI_SUCCESS) {
    material->Get(AI_MATKEY_COLOR_DIFFUSE, color);
  }
  return {color.r, color.g, color.b};
}

// The base colour texture's path as the file writes it, or "".
std::string material_texture(const aiMaterial* material) {
  aiString path;
  for (aiTextureType type : {aiTextureType_BASE_COLOR, aiTextureType_DIFFUSE}) {
    if (material->GetTextureCount(type) > 0 && material->GetTexture(type, 0, &path) == AI_SUCCESS &&
        path.length > 0) {
      std::string text = path.C_Str();
      std::replace(text.begin(), text.end(), '\\', '/');
      return text;
    }
  }
  return "";
}

glm::mat4 to_glm(const aiMatrix4x4& m) {
  return glm::transpose(glm::make_mat4(&m.a1));  // Assimp is row-major
}

// File units to metres and the file's up axis to +y, from the metadata Assimp passes on (FBX
// writes UnitScaleFactor in centimetres per unit and UpAxis 0/1/2 with a sign).
glm::mat4 root_correction(const aiScene* scene, std::string* what) {
  glm::mat4 correction(1.0f);
  if (scene->mMetaData == nullptr) return correction;
  const aiMetadata& meta = *scene->mMetaData;
  int32_t up_axis = 1, up_sign = 1;
  double unit_scale = 1.0;
  float unit_scale_f = 1.0f;
  if (meta.Get("UnitScaleFactor", unit_scale)) {
  } else if (meta.Get("UnitScaleFactor", unit_scale_f)) {
    unit_scale = unit_scale_f;
  } else {
    unit_scale = 100.0;  // no unit metadata: the file's units are metres
  }
  meta.Get("UpAxis", up_axis);
  meta.Get("UpAxisSign", up_sign);
  std::ostringstream text;
  if (unit_scale > 0.0 && std::isfinite(unit_scale) && std::abs(unit_scale - 100.0) > 1e-6) {
    const float metres = static_cast<float>(unit_scale / 100.0);
    correction = glm::scale(glm::mat4(1.0f), glm::vec3(metres));
    text << "units x" << metres << " (UnitScaleFactor " << unit_scale << " cm)";
  }
  if (up_axis == 2 || (up_axis == 1 && up_sign < 0) || up_axis == 0) {
    glm::mat4 rotation(1.0f);
    const float sign = up_sign < 0 ? -1.0f : 1.0f;
    if (up_axis == 2) {  // z up: rotate -90 degrees about x so +z becomes +y
      rotation = glm::rotate(glm::mat4(1.0f), -sign * glm::half_pi<float>(), glm::vec3(1, 0, 0));
    } else if (up_axis == 0) {  // x up: rotate +90 degrees about z so +x becomes +y
      rotation = glm::rotate(glm::mat4(1.0f), sign * glm::half_pi<float>(), glm::vec3(0, 0, 1));
    } else {
      rotation = glm::rotate(glm::mat4(1.0f), glm::pi<float>(), glm::vec3(1, 0, 0));
    }
    correction = rotation * correction;
    text << (text.tellp() > 0 ? ", " : "") << (sign < 0 ? "-" : "+") << "xyz"[up_axis]
         << " up turned to +y";
  }
  *what = text.str();
  return correction;
}

// OBJ files name their material files with `mtllib` lines; Assimp silently falls back to a
// default material when one is missing, so look for them ourselves.
void check_obj_materials(const std::string& path, std::vector<std::string>* warnings) {
  std::ifstream in(path);
  std::string line;
  bool uses_materials = false, names_library = false;
  while (std::getline(in, line)) {
    std::istringstream words(line);
    std::string keyword;
    words >> keyword;
    if (keyword == "usemtl") uses_materials = true;
    if (keyword != "mtllib") continue;
    names_library = true;
    std::string name;
    std::getline(words >> std::ws, name);
    while (!name.empty() && (name.back() == '\r' || name.back() == ' ')) name.pop_back();
    const fs::path library = fs::path(path).parent_path() / name;
    std::error_code error;
    if (!fs::is_regular_file(library, error)) {
      warnings->push_back(
          "material file '" + library.lexically_normal().string() + "' (mtllib of '" + path +
          "') is missing; its materials render grey 0.6 (Assimp's default), untextured");
    }
  }
  if (uses_materials && !names_library) {
    warnings->push_back("'" + path +
                        "' uses materials (usemtl) but names no material file (mtllib); they "
                        "render grey 0.6 (Assimp's default), untextured");
  }
}

bool is_obj(const std::string& path) {
  std::string extension = fs::path(path).extension().string();
  std::transform(extension.begin(), extension.end(), extension.begin(), ::tolower);
  return extension == ".obj";
}

void read_materials(const aiScene* scene, const std::string& path, Model* model) {
  // A bare file name ("coral.obj", a graph run from its own folder) has no parent path: its
  // folder is the current one, as for "./coral.obj".
  fs::path folder = fs::path(path).parent_path();
  if (folder.empty()) folder = ".";
  for (unsigned m = 0; m < scene->mNumMaterials; ++m) {
    const aiMaterial* in = scene->mMaterials[m];
    ModelMaterial material;
    material.name = in->GetName().C_Str();
    material.color = material_color(in);
    const std::string texture = material_texture(in);
    if (!texture.empty() && texture[0] == '*') {
      material.texture = texture;
      material.embedded = true;
    } else if (!texture.empty()) {
      const std::string resolved = (folder / texture).lexically_normal().string();
      std::error_code error;
      // A texture must lie inside the mesh's folder (mesh_file_checks.h), like every file a
      // mesh refers to: a file from elsewhere is refused by name, never read.
      if (const std::string problem = reference_problem(folder.string(), texture);
          !problem.empty() && fs::exists(resolved, error)) {
        model->warnings.push_back("texture of material '" + material.name + "' in '" + path +
                                  "' refused: " + problem + "; using its colour untextured");
      } else if (fs::is_regular_file(resolved, error)) {
        material.texture = resolved;
      } else {
        char color[64];
        std::snprintf(color, sizeof(color), "(%.3g, %.3g, %.3g)", material.color.r,
                      material.color.g, material.color.b);
        model->warnings.push_back("texture '" + resolved + "' of material '" + material.name +
                                  "' in '" + path + "' is missing; using its colour " + color +
                                  " untextured");
      }
    }
    model->materials.push_back(std::move(material));
  }
  for (unsigned t = 0; t < scene->mNumTextures; ++t) {
    const aiTexture* in = scene->mTextures[t];
    if (in->mHeight != 0) continue;  // raw texels: no exporter we read writes them
    EmbeddedTexture texture;
    const auto* bytes = reinterpret_cast<const unsigned char*>(in->pcData);
    texture.bytes.assign(bytes, bytes + in->mWidth);
    texture.extension = in->achFormatHint[0] != '\0' ? in->achFormatHint : "png";
    model->embedded["*" + std::to_string(t)] = std::move(texture);
  }
}

void read_meshes(const aiScene* scene, Model* model) {
  for (unsigned m = 0; m < scene->mNumMeshes; ++m) {
    const aiMesh* in = scene->mMeshes[m];
    ModelMesh out;
    out.material = in->mMaterialIndex;
    const glm::vec3 base = in->mMaterialIndex < model->materials.size()
                               ? model->materials[in->mMaterialIndex].color
                               : glm::vec3(0.8f);
    if ((in->mPrimitiveTypes & aiPrimitiveType_TRIANGLE) != 0) {
      MeshBuilder builder(out.data);
      for (unsigned v = 0; v < in->mNumVertices; ++v) {
        glm::vec3 p(in->mVertices[v].x, in->mVertices[v].y, in->mVertices[v].z);
        glm::vec3 n(0, 1, 0);
        if (in->HasNormals()) n = {in->mNormals[v].x, in->mNormals[v].y, in->mNormals[v].z};
        glm::vec3 c = base;
        if (in->HasVertexColors(0)) {
          c *= glm::vec3(in->mColors[0][v].r, in->mColors[0][v].g, in->mColors[0][v].b);
        }
        builder.vertex(p, n, c);
        if (in->HasTextureCoords(0)) {
          out.data.uvs.insert(out.data.uvs.end(),
                              {in->mTextureCoords[0][v].x, in->mTextureCoords[0][v].y});
        }
      }
      for (unsigned f = 0; f < in->mNumFaces; ++f) {
        const aiFace& face = in->mFaces[f];
        if (face.mNumIndices != 3) continue;
        builder.triangle(face.mIndices[0], face.mIndices[1], face.mIndices[2]);
      }
    }
    model->meshes.push_back(std::move(out));  // kept (even empty) so node indices hold
  }
}

void read_nodes(const aiNode* node, int parent, Model* model) {
  ModelNode out;
  out.name = node->mName.C_Str();
  out.parent = parent;
  out.local = to_glm(node->mTransformation);
  for (unsigned m = 0; m < node->mNumMeshes; ++m) out.meshes.push_back(node->mMeshes[m]);
  const int index = static_cast<int>(model->nodes.size());
  model->nodes.push_back(std::move(out));
  for (unsigned c = 0; c < node->mNumChildren; ++c) read_nodes(node->mChildren[c], index, model);
}

void read_animation(const aiScene* scene, Model* model) {
  if (scene->mNumAnimations == 0) return;
  const aiAnimation* animation = scene->mAnimations[0];
  const double ticks = animation->mTicksPerSecond > 0.0 ? animation->mTicksPerSecond : 25.0;
  model->duration = animation->mDuration / ticks;
  for (unsigned c = 0; c < animation->mNumChannels; ++c) {
    const aiNodeAnim* in = animation->mChannels[c];
    NodeChannel channel;
    for (unsigned k = 0; k < in->mNumPositionKeys; ++k) {
      const aiVector3D& v = in->mPositionKeys[k].mValue;
      channel.positions.push_back({in->mPositionKeys[k].mTime / ticks, glm::vec3(v.x, v.y, v.z)});
    }
    for (unsigned k = 0; k < in->mNumRotationKeys; ++k) {
      const aiQuaternion& q = in->mRotationKeys[k].mValue;
      channel.rotations.push_back(
          {in->mRotationKeys[k].mTime / ticks, glm::quat(q.w, q.x, q.y, q.z)});
    }
    for (unsigned k = 0; k < in->mNumScalingKeys; ++k) {
      const aiVector3D& v = in->mScalingKeys[k].mValue;
      channel.scales.push_back({in->mScalingKeys[k].mTime / ticks, glm::vec3(v.x, v.y, v.z)});
    }
    for (ModelNode& node : model->nodes) {
      if (node.name == in->mNodeName.C_Str())
        node.channel = static_cast<int>(model->channels.size());
    }
    model->channels.push_back(std::move(channel));
  }
}

template <typename T, typename Mix>
T sample(const std::vector<Key<T>>& keys, double time, const T& fallback, Mix mix) {
  if (keys.empty()) return fallback;
  if (time <= keys.front().time) return keys.front().value;
  if (time >= keys.back().time) return keys.back().value;
  auto next = std::upper_bound(keys.begin(), keys.end(), time,
                               [](double t, const Key<T>& key) { return t < key.time; });
  auto previous = next - 1;
  const double span = next->time - previous->time;
  const float f = span > 0.0 ? static_cast<float>((time - previous->time) / span) : 0.0f;
  return mix(previous->value, next->value, f);
}

glm::mat4 animated_local(const ModelNode& node, const NodeChannel& channel, double time) {
  // A channel replaces the node's transform; components without keys keep the rest pose's.
  glm::vec3 scale, translation, skew;
  glm::quat rotation;
  glm::vec4 perspective;
  const glm::mat4& rest = node.local;
  translation = glm::vec3(rest[3]);
  scale = glm::vec3(glm::length(glm::vec3(rest[0])), glm::length(glm::vec3(rest[1])),
                    glm::length(glm::vec3(rest[2])));
  rotation = glm::quat_cast(glm::mat3(glm::vec3(rest[0]) / scale.x, glm::vec3(rest[1]) / scale.y,
                                      glm::vec3(rest[2]) / scale.z));
  (void)skew;
  (void)perspective;
  auto lerp = [](const glm::vec3& a, const glm::vec3& b, float f) { return glm::mix(a, b, f); };
  auto slerp = [](const glm::quat& a, const glm::quat& b, float f) { return glm::slerp(a, b, f); };
  translation = sample(channel.positions, time, translation, lerp);
  rotation = sample(channel.rotations, time, rotation, slerp);
  scale = sample(channel.scales, time, scale, lerp);
  return glm::translate(glm::mat4(1.0f), translation) * glm::mat4_cast(rotation) *
         glm::scale(glm::mat4(1.0f), scale);
}

}  // namespace

std::string load_model(const std::string& path, Model* model) {
  *model = Model{};
  model->path = path;
  if (path.empty()) return "no file given: set the `path` parameter to an OBJ, glTF or FBX file";
  Assimp::Importer importer;
  std::string error;  // mesh_import.h: regular files in the mesh's folder, checked headers
  const aiScene* scene = read_mesh_file(importer, path, kImportFlags, &error);
  if (scene == nullptr) return error;
  if (scene->mRootNode == nullptr) {
    return "could not read '" + path + "': the file has no node hierarchy (re-export it)";
  }
  if (is_obj(path)) check_obj_materials(path, &model->warnings);
  read_materials(scene, path, model);
  read_meshes(scene, model);
  read_nodes(scene->mRootNode, -1, model);
  read_animation(scene, model);
  model->root_correction = root_correction(scene, &model->correction);
  bool any_triangles = false;
  for (const ModelMesh& mesh : model->meshes) any_triangles |= !mesh.data.indices.empty();
  if (!any_triangles) {
    return "'" + path + "' holds no triangle meshes (points and lines are not rendered)";
  }
  return "";
}

std::vector<Instance> model_instances(const Model& model, double time) {
  if (model.duration > 0.0) {
    time = std::fmod(time, model.duration);
    if (time < 0.0) time += model.duration;
  }
  std::vector<glm::mat4> global(model.nodes.size());
  std::vector<Instance> out;
  for (size_t i = 0; i < model.nodes.size(); ++i) {
    const ModelNode& node = model.nodes[i];
    const glm::mat4 local =
        node.channel >= 0 ? animated_local(node, model.channels[node.channel], time) : node.local;
    global[i] = (node.parent >= 0 ? global[node.parent] : model.root_correction) * local;
    for (uint32_t mesh : node.meshes) {
      if (mesh < model.meshes.size() && !model.meshes[mesh].data.indices.empty()) {
        out.push_back({mesh, global[i]});
      }
    }
  }
  return out;
}

void check_model_file(const std::string& path, std::vector<std::string>* errors,
                      std::vector<std::string>* warnings) {
  Model model;
  if (std::string error = load_model(path, &model); !error.empty()) {
    errors->push_back(error);
    return;
  }
  warnings->insert(warnings->end(), model.warnings.begin(), model.warnings.end());
}

std::string load_model_file(const std::string& path, Preset* preset, const aq::Context& ctx,
                            TextureCache& textures) {
  *preset = Preset{};
  Model model;
  if (std::string error = load_model(path, &model); !error.empty()) return error;
  apply_model_textures(ctx, model, textures);
  for (const std::string& warning : model.warnings) ctx.warn(warning);
  for (const Instance& instance : model_instances(model, 0.0)) {
    MeshData mesh = model.meshes[instance.mesh].data;
    mesh.model = instance.transform;
    mesh.object_id = static_cast<uint32_t>(preset->static_meshes.size() + 1);
    preset->static_meshes.push_back(std::move(mesh));
  }
  return "";
}

}  // namespace scene
