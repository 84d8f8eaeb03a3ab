// What a mesh file may declare before Assimp reads it. Assimp trusts headers: a 177-byte PLY
// declaring 2e9 vertices makes it reserve 23 GB, a GLB chunk length of 2 GB is allocated as
// given, a glTF node hierarchy 20,000 deep overflows its recursive reader, and files a mesh
// refers to (glTF buffers and images, OBJ's mtllib) are opened wherever they point. These
// checks read only the header (PLY), the JSON (glTF, GLB) or the record structure (FBX) and refuse,
// by name, what cannot be right: declared sizes larger than the file holds or than the memory
// budget allows, hierarchies deeper than kMaxMeshHierarchyDepth or with cycles, and references
// outside the mesh's folder. No message quotes a file's content. Pure (no Assimp): the fuzzer calls
// them.
#pragma once

#include <cstdint>
#include <functional>
#include <string>
#include <string_view>

namespace scene {

inline constexpr int kMaxMeshHierarchyDepth = 1024;
// Polygons with more vertices than this must be convex (they get a linear-time fan); Assimp's
// ear clipping is quadratic (5,000 vertices: ~2 s) so larger concave ones are refused.
inline constexpr uint32_t kMaxConcavePolygonVertices = 4096;
// JSON nesting in a glTF file (its hierarchy lives in indices, not nesting).
inline constexpr int kMaxGltfJsonNesting = 64;

// Empty when `reference` (as written in a mesh file in `folder`) resolves, through any links,
// to a regular file inside `folder`; else why not (naming the reference, never its content).
std::string reference_problem(const std::string& folder, const std::string& reference);

// Empty when `canonical` lies inside `folder_canonical` (both canonical, absolute).
bool is_inside_folder(const std::string& folder_canonical, const std::string& canonical);

// PLY: `bytes` is the file's start (at least up to end_header), `file_size` its whole size.
std::string check_ply_header(std::string_view bytes, uint64_t file_size, uint64_t budget);

// glTF JSON text (a .gltf file, or a GLB's JSON chunk with `bin_chunk_bytes` of binary, -1
// when there is no BIN chunk). External buffers are checked in `folder` when it is not empty.
std::string check_gltf_json(std::string_view json, const std::string& folder,
                            int64_t bin_chunk_bytes, uint64_t budget);

// GLB: the whole file's bytes (chunk lengths against the file's size, then its JSON).
std::string check_glb(std::string_view bytes, const std::string& folder, uint64_t budget);

// Any mesh file: Assimp reads most formats whole into memory and then parses them (a 200 GB
// sparse .obj was read whole): a file larger than the budget over kFileBytesInMemory is
// refused before it is opened by Assimp.
inline constexpr uint64_t kFileBytesInMemory = 4;
std::string check_mesh_file_size(uint64_t file_size, uint64_t budget);

// OBJ: every object, group or material change becomes a mesh of its own in Assimp, with a
// fixed cost in memory and time (150,000 one-triangle objects in 2.6 MB took 1.5 GB and 37 s).
// Counts them, and refuses more than kMaxObjMeshes or than the budget allows.
inline constexpr uint64_t kMaxObjMeshes = 20000;
std::string check_obj(std::string_view bytes, uint64_t budget);
// The same in parts, for a file read in chunks (each chunk ends at a line break).
uint64_t count_obj_meshes(std::string_view bytes);
std::string obj_meshes_problem(uint64_t meshes, uint64_t budget);

// PLY's body: every list (a face's vertex indices) declares its length before its items and
// Assimp reserves that length (a 220-byte file declaring 268 M indices took 2.2 GB). Walks a
// binary body's elements, or an ASCII body's list counts, refusing a list longer than the
// rest of the file holds. `read(offset, dst, n)` reads n bytes of the file at offset (false
// past its end), so a large file is walked without being held in memory.
std::string check_ply_body(std::string_view header, uint64_t file_size,
                           const std::function<bool(uint64_t, char*, size_t)>& read);

// Dispatches on the extension (lower case, without dot): ply, gltf, glb; others pass.
std::string check_mesh_file_bytes(const std::string& ext, std::string_view bytes,
                                  uint64_t file_size, const std::string& folder, uint64_t budget);

}  // namespace scene
