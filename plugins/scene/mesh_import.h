// Reading a mesh file with Assimp without trusting it (see mesh_file_checks.h for why):
//   path: a regular file, no NUL ─► header checks (PLY, glTF, GLB) ─► Assimp reads through an
//   IOSystem that opens only regular files inside the mesh's folder ─► node hierarchy depth
//   checked ─► large convex polygons fanned in linear time, large concave ones refused
//   ─► the caller's post-processing (triangulation...).
// Assimp runs on a thread with a large stack so that recursion in formats without a header
// check cannot overflow. Errors name the file and say what to fix; none quotes file content.
#pragma once

#include <string>

#include <assimp/Importer.hpp>

struct aiScene;

namespace scene {

// Reads `path` into `importer` and applies `post_processing` (aiProcess_* flags). Returns the
// scene, or nullptr and a message in `error`.
const aiScene* read_mesh_file(Assimp::Importer& importer, const std::string& path,
                              unsigned post_processing, std::string* error);

}  // namespace scene
