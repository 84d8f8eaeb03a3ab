// Loads a user scene (OBJ, glTF, FBX... whatever Assimp reads) into a Preset: one static mesh
// per Assimp mesh, node transforms baked, triangulated, flat normals generated where the file
// has none (smoothing happens later, like for procedural meshes), colours from the material's
// base colour (glTF) or diffuse colour (OBJ's Kd), times vertex colours when present.
#include "mesh_import.h"
#include "presets.h"

#include <assimp/material.h>
#include <assimp/postprocess.h>
#include <assimp/scene.h>
#include <assimp/Importer.hpp>

namespace scene {

namespace {

glm::vec3 material_color(const aiMaterial* material) {
  aiColor4D color(0.8f, 0.8f, 0.8f, 1.0f);
  if (material == nullptr) return {color.r, color.g, color.b};
  if (material->Get(AI_MATKEY_BASE_COLOR, color) != AI_SUCCESS) {
    material->Get(AI_MATKEY_COLOR_DIFFUSE, color);
  }
  return {color.r, color.g, color.b};
}

}  // namespace

std::string load_model_file(const std::string& path, Preset* preset) {
  *preset = Preset{};
  if (path.empty()) return "no file given: set the `path` parameter to an OBJ or glTF file";
  Assimp::Importer importer;
  std::string error;  // mesh_import.h: regular files in the mesh's folder, checked headers
  const aiScene* scene =
      read_mesh_file(importer, path,
                     aiProcess_Triangulate | aiProcess_PreTransformVertices | aiProcess_GenNormals |
                         aiProcess_SortByPType | aiProcess_FindInvalidData,
                     &error);
  if (scene == nullptr) return error;
  for (unsigned m = 0; m < scene->mNumMeshes; ++m) {
    const aiMesh* in = scene->mMeshes[m];
    if ((in->mPrimitiveTypes & aiPrimitiveType_TRIANGLE) == 0 || in->mNumVertices == 0) continue;
    glm::vec3 base = in->mMaterialIndex < scene->mNumMaterials
                         ? material_color(scene->mMaterials[in->mMaterialIndex])
                         : glm::vec3(0.8f);
    MeshData mesh;
    MeshBuilder builder(mesh);
    for (unsigned v = 0; v < in->mNumVertices; ++v) {
      glm::vec3 p(in->mVertices[v].x, in->mVertices[v].y, in->mVertices[v].z);
      glm::vec3 n(0, 1, 0);
      if (in->HasNormals()) n = {in->mNormals[v].x, in->mNormals[v].y, in->mNormals[v].z};
      glm::vec3 c = base;
      if (in->HasVertexColors(0)) {
        c *= glm::vec3(in->mColors[0][v].r, in->mColors[0][v].g, in->mColors[0][v].b);
      }
      builder.vertex(p, n, c);
    }
    for (unsigned f = 0; f < in->mNumFaces; ++f) {
      const aiFace& face = in->mFaces[f];
      if (face.mNumIndices != 3) continue;
      builder.triangle(face.mIndices[0], face.mIndices[1], face.mIndices[2]);
    }
    if (mesh.indices.empty()) continue;
    mesh.object_id = static_cast<uint32_t>(preset->static_meshes.size() + 1);
    preset->static_meshes.push_back(std::move(mesh));
  }
  if (preset->static_meshes.empty()) {
    return "'" + path + "' holds no triangle meshes (points and lines are not rendered)";
  }
  return "";
}

}  // namespace scene
