#include "mesh_import.h"

#include "mesh_file_checks.h"

#include <aquarelle/sdk/regular_file.hpp>

#include <assimp/DefaultIOSystem.h>
#include <assimp/scene.h>
#include <assimp/IOStream.hpp>

#include <pthread.h>
#include <unistd.h>
#include <glm/glm.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <functional>
#include <memory>
#include <utility>
#include <vector>

namespace scene {

namespace {

// Assimp's readers and post-processing steps recurse over the node hierarchy; 256 MiB of
// (lazily committed) stack keeps far deeper files than kMaxMeshHierarchyDepth from crashing.
constexpr size_t kImportStackBytes = size_t{256} << 20;
// Polygons above this size are triangulated here when convex (Assimp's ear clipping is
// quadratic); smaller ones are left to Assimp.
constexpr uint32_t kFanFromVertices = 256;
// A header, or a glTF's JSON, is read whole up to this size for the checks.
constexpr uint64_t kPlyHeaderBytes = uint64_t{1} << 20;

std::string lowercase_extension(const std::string& path) {
  std::string ext = std::filesystem::path(path).extension().string();
  if (!ext.empty() && ext[0] == '.') ext.erase(0, 1);
  for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return ext;
}

// One line of printable ASCII, at most 200 characters: Assimp's messages may carry bytes of
// the file they failed on.
std::string printable(const std::string& text) {
  std::string out;
  for (char c : text) {
    if (out.size() >= 200) {
      out += "...";
      break;
    }
    out += (c >= 32 && c < 127) ? c : ' ';
  }
  return out;
}

class FileStream final : public Assimp::IOStream {
 public:
  explicit FileStream(std::FILE* file) : file_(file) {}
  ~FileStream() override { std::fclose(file_); }
  size_t Read(void* buffer, size_t size, size_t count) override {
    return std::fread(buffer, size, count, file_);
  }
  size_t Write(const void*, size_t, size_t) override { return 0; }
  aiReturn Seek(size_t offset, aiOrigin origin) override {
    const int whence = origin == aiOrigin_SET   ? SEEK_SET
                       : origin == aiOrigin_CUR ? SEEK_CUR
                                                : SEEK_END;
    return std::fseek(file_, static_cast<long>(offset), whence) == 0 ? aiReturn_SUCCESS
                                                                     : aiReturn_FAILURE;
  }
  size_t Tell() const override { return static_cast<size_t>(std::ftell(file_)); }
  size_t FileSize() const override {
    const long at = std::ftell(file_);
    std::fseek(file_, 0, SEEK_END);
    const long size = std::ftell(file_);
    std::fseek(file_, at, SEEK_SET);
    return size < 0 ? 0 : static_cast<size_t>(size);
  }
  void Flush() override {}

 private:
  std::FILE* file_;
};

// Opens for reading only regular files inside the mesh's folder; everything else is refused
// and remembered by name, so the load fails saying which reference was refused (Assimp would
// otherwise go on without, say, the materials).
class ConfinedIOSystem final : public Assimp::DefaultIOSystem {
 public:
  explicit ConfinedIOSystem(std::string folder) : folder_(std::move(folder)) {}

  // Assimp asks Exists before opening optional files (OBJ's mtllib): a refusal is remembered
  // here too, or it would quietly go on without them. A missing file is Assimp's to report.
  bool Exists(const char* file) const override {
    const std::string why = allowed(file);
    if (!why.empty() && !aq::files::regular_file_problem(file).starts_with("no such file")) {
      refuse(why);
    }
    return why.empty();
  }

  Assimp::IOStream* Open(const char* file, const char* mode) override {
    if (mode != nullptr && std::string(mode).find_first_of("wa+") != std::string::npos) {
      refuse("it asked to write '" + std::string(file) + "'");
      return nullptr;
    }
    if (std::string why = allowed(file); !why.empty()) {
      // A missing file inside the folder is the format's to handle (OBJ: a missing mtllib
      // renders with the default material, which the loader warns about); anything else
      // (outside the folder, not a regular file) is refused.
      if (!is_missing_inside(file)) refuse(why);
      return nullptr;
    }
    std::string why;
    const int fd = aq::files::open_regular_file(file, &why);
    if (fd < 0) {
      refuse("'" + relative(file) + "': " + why);
      return nullptr;
    }
    std::FILE* stream = ::fdopen(fd, "rb");
    if (stream == nullptr) {
      ::close(fd);
      return nullptr;
    }
    return new FileStream(stream);
  }

  void Close(Assimp::IOStream* file) override { delete file; }

  const std::vector<std::string>& refusals() const { return refusals_; }

 private:
  std::string relative(const std::string& file) const {
    std::error_code ec;
    auto rel = std::filesystem::path(file).lexically_relative(folder_);
    return ec || rel.empty() ? file : rel.string();
  }
  bool is_missing_inside(const std::string& file) const {
    std::error_code ec;
    const auto resolved = std::filesystem::weakly_canonical(file, ec);
    return !ec && is_inside_folder(folder_, resolved.string()) &&
           aq::files::regular_file_problem(resolved.string()).starts_with("no such file");
  }
  std::string allowed(const std::string& file) const {
    std::error_code ec;
    const auto resolved = std::filesystem::weakly_canonical(file, ec);
    if (ec || !is_inside_folder(folder_, resolved.string())) {
      return "it refers to '" + relative(file) + "', which lies outside the mesh's folder " +
             folder_ + " (files a mesh refers to must be inside its folder)";
    }
    if (std::string why = aq::files::regular_file_problem(resolved.string()); !why.empty()) {
      return "it refers to '" + relative(file) + "': " + why;
    }
    return "";
  }
  void refuse(const std::string& why) const {
    if (std::find(refusals_.begin(), refusals_.end(), why) == refusals_.end()) {
      refusals_.push_back(why);
    }
  }

  std::string folder_;
  mutable std::vector<std::string> refusals_;
};

// Runs `work` on a thread with kImportStackBytes of stack, and waits for it.
void run_with_large_stack(const std::function<void()>& work) {
  pthread_attr_t attributes;
  pthread_attr_init(&attributes);
  pthread_attr_setstacksize(&attributes, kImportStackBytes);
  pthread_t thread;
  auto* task = new std::function<void()>(work);
  auto entry = [](void* data) -> void* {
    std::unique_ptr<std::function<void()>> job(static_cast<std::function<void()>*>(data));
    (*job)();
    return nullptr;
  };
  if (pthread_create(&thread, &attributes, entry, task) != 0) {
    delete task;
    work();  // no thread to be had: the ordinary stack, as before
  } else {
    pthread_join(thread, nullptr);
  }
  pthread_attr_destroy(&attributes);
}

int hierarchy_depth(const aiNode* root) {
  int deepest = 0;
  std::vector<std::pair<const aiNode*, int>> pending{{root, 1}};
  while (!pending.empty()) {
    auto [node, depth] = pending.back();
    pending.pop_back();
    if (node == nullptr) continue;
    deepest = std::max(deepest, depth);
    if (deepest > kMaxMeshHierarchyDepth) return deepest;
    for (unsigned i = 0; i < node->mNumChildren; ++i)
      pending.push_back({node->mChildren[i], depth + 1});
  }
  return deepest;
}

// Convex (and simple: it winds once) in the plane of its Newell normal. Files round their
// coordinates: in a 200,000-gon each true turn is 3e-5 rad while rounding to 7 digits moves
// an edge's direction by up to 1e-3 rad, so turns back by less than kConvexTolerance count as
// straight (a fan over such a dent is off by a sliver far below a pixel).
constexpr double kConvexTolerance = 0.01;
bool is_convex(const aiMesh& mesh, const aiFace& face) {
  const unsigned n = face.mNumIndices;
  auto at = [&](unsigned i) {
    const aiVector3D& v = mesh.mVertices[face.mIndices[i % n]];
    return glm::dvec3(v.x, v.y, v.z);
  };
  glm::dvec3 normal(0.0);
  for (unsigned i = 0; i < n; ++i) {
    const glm::dvec3 a = at(i), b = at(i + 1);
    normal +=
        glm::dvec3((a.y - b.y) * (a.z + b.z), (a.z - b.z) * (a.x + b.x), (a.x - b.x) * (a.y + b.y));
  }
  const double length = glm::length(normal);
  if (!(length > 0.0)) return false;
  normal /= length;
  double turning = 0.0;
  glm::dvec3 previous = at(0) - at(n - 1);
  for (unsigned i = 0; i < n; ++i) {
    const glm::dvec3 edge = at(i + 1) - at(i);
    if (glm::dot(edge, edge) == 0.0) continue;  // repeated vertex
    const double sine = glm::dot(glm::cross(previous, edge), normal);
    const double cosine = glm::dot(previous, edge);
    const double turn = std::atan2(sine, cosine);
    if (turn < -kConvexTolerance) return false;
    turning += turn;
    previous = edge;
  }
  return std::abs(turning - 2.0 * M_PI) < 1e-3;
}

// Fans large convex polygons (linear time), refuses large concave ones. Empty or why not.
std::string triangulate_large_polygons(aiScene& scene) {
  for (unsigned m = 0; m < scene.mNumMeshes; ++m) {
    aiMesh& mesh = *scene.mMeshes[m];
    size_t total = 0;
    bool any = false;
    for (unsigned f = 0; f < mesh.mNumFaces; ++f) {
      const aiFace& face = mesh.mFaces[f];
      if (face.mNumIndices <= kFanFromVertices) {
        ++total;
        continue;
      }
      if (!is_convex(mesh, face)) {
        if (face.mNumIndices > kMaxConcavePolygonVertices) {
          return "mesh " + std::to_string(m) + " has a concave polygon of " +
                 std::to_string(face.mNumIndices) + " vertices; at most " +
                 std::to_string(kMaxConcavePolygonVertices) +
                 " are supported for concave polygons (triangulate it in your modelling tool)";
        }
        ++total;
        continue;
      }
      any = true;
      total += face.mNumIndices - 2;
    }
    if (!any) continue;
    auto* faces = new aiFace[total];
    size_t out = 0;
    for (unsigned f = 0; f < mesh.mNumFaces; ++f) {
      aiFace& face = mesh.mFaces[f];
      if (face.mNumIndices <= kFanFromVertices || !is_convex(mesh, face)) {
        std::swap(faces[out].mNumIndices, face.mNumIndices);
        std::swap(faces[out].mIndices, face.mIndices);
        ++out;
        continue;
      }
      for (unsigned i = 1; i + 1 < face.mNumIndices; ++i) {
        faces[out].mNumIndices = 3;
        faces[out].mIndices =
            new unsigned[3]{face.mIndices[0], face.mIndices[i], face.mIndices[i + 1]};
        ++out;
      }
    }
    delete[] mesh.mFaces;
    mesh.mFaces = faces;
    mesh.mNumFaces = static_cast<unsigned>(total);
    // The primitive types must describe the faces as they are now: Assimp's triangulation
    // step asserts that a mesh flagged as holding polygons really holds one.
    unsigned types = 0;
    for (unsigned f = 0; f < mesh.mNumFaces; ++f) {
      const unsigned n = mesh.mFaces[f].mNumIndices;
      types |= n == 1   ? aiPrimitiveType_POINT
               : n == 2 ? aiPrimitiveType_LINE
               : n == 3 ? aiPrimitiveType_TRIANGLE
                        : aiPrimitiveType_POLYGON;
    }
    mesh.mPrimitiveTypes = types;
  }
  return "";
}

// Reads a PLY body through a 64 KiB window for check_ply_body.
std::function<bool(uint64_t, char*, size_t)> ply_reader(int fd) {
  auto window = std::make_shared<std::pair<uint64_t, std::string>>(UINT64_MAX, std::string());
  return [fd, window](uint64_t offset, char* dst, size_t n) {
    auto& [start, bytes] = *window;
    if (offset < start || offset + n > start + bytes.size()) {
      bytes.resize(64 << 10);
      const ssize_t got = ::pread(fd, bytes.data(), bytes.size(), static_cast<off_t>(offset));
      bytes.resize(got > 0 ? static_cast<size_t>(got) : 0);
      start = offset;
      if (n > bytes.size()) return false;
    }
    std::memcpy(dst, bytes.data() + (offset - start), n);
    return true;
  };
}

std::string header_problem(const std::string& path, const std::string& folder) {
  const std::string ext = lowercase_extension(path);
  const uint64_t budget = aq::files::memory_budget_bytes();
  const uint64_t size = aq::files::regular_file_size(path);
  if (std::string why = check_mesh_file_size(size, budget); !why.empty()) return why;
  if (ext != "ply" && ext != "gltf" && ext != "glb" && ext != "fbx" && ext != "obj") return "";
  std::string bytes, why;
  if (ext == "ply") {
    std::string header;
    const int fd = aq::files::open_regular_file(path, &why);
    if (fd < 0) return why;
    header.resize(static_cast<size_t>(std::min(size, kPlyHeaderBytes)));
    const ssize_t got = ::pread(fd, header.data(), header.size(), 0);
    header.resize(got > 0 ? static_cast<size_t>(got) : 0);
    std::string problem = check_ply_header(header, size, budget);
    if (problem.empty()) problem = check_ply_body(header, size, ply_reader(fd));
    ::close(fd);
    return problem;
  }
  if (ext == "obj") {  // read in chunks: the file can be large, only its lines are counted
    const int fd = aq::files::open_regular_file(path, &why);
    if (fd < 0) return why;
    uint64_t meshes = 0;
    std::string chunk(1 << 20, '\0'), carry;
    for (ssize_t got; (got = ::read(fd, chunk.data(), chunk.size())) > 0;) {
      carry.append(chunk.data(), static_cast<size_t>(got));
      const size_t last = carry.rfind('\n');
      if (last == std::string::npos) continue;
      meshes += count_obj_meshes(std::string_view(carry).substr(0, last + 1));
      carry.erase(0, last + 1);
    }
    ::close(fd);
    return obj_meshes_problem(meshes + count_obj_meshes(carry), budget);
  }
  if (!aq::files::read_regular_file(path, budget, &bytes, &why)) return why;
  return check_mesh_file_bytes(ext, bytes, size, folder, budget);
}

}  // namespace

const aiScene* read_mesh_file(Assimp::Importer& importer, const std::string& path,
                              unsigned post_processing, std::string* error) {
  auto fail = [&](const std::string& why) -> const aiScene* {
    *error = "could not read '" + path + "': " + why;
    return nullptr;
  };
  if (std::string why = aq::files::regular_file_problem(path); !why.empty()) {
    return fail(why + " (a relative path is relative to the graph file's folder)");
  }
  // Assimp reads dozens of formats by content; only the documented ones are let through (each
  // format reader is attack surface), chosen by extension as Assimp chooses its reader.
  const std::string ext = lowercase_extension(path);
  if (ext != "obj" && ext != "gltf" && ext != "glb" && ext != "ply" && ext != "fbx" &&
      ext != "stl") {
    return fail("'." + ext + "' files are not read; use OBJ, glTF/GLB, FBX, PLY or STL");
  }
  std::error_code ec;
  // The folder the path names (Assimp resolves references from it), links resolved.
  const std::string folder =
      std::filesystem::weakly_canonical(std::filesystem::absolute(path, ec).parent_path(), ec)
          .string();
  if (std::string why = header_problem(path, folder); !why.empty()) return fail(why);

  auto* io = new ConfinedIOSystem(folder);
  importer.SetIOHandler(io);  // the importer owns and deletes it
  const aiScene* scene = nullptr;
  std::string problem;
  run_with_large_stack([&] {
    scene = importer.ReadFile(path, 0);
    if (!io->refusals().empty() || scene == nullptr || scene->mRootNode == nullptr) return;
    if (hierarchy_depth(scene->mRootNode) > kMaxMeshHierarchyDepth) {
      problem = "its node hierarchy is more than " + std::to_string(kMaxMeshHierarchyDepth) +
                " levels deep (flatten it in your modelling tool)";
      return;
    }
    problem = triangulate_large_polygons(*const_cast<aiScene*>(scene));
    if (problem.empty()) scene = importer.ApplyPostProcessing(post_processing);
  });
  if (!io->refusals().empty()) return fail(io->refusals().front());
  if (!problem.empty()) return fail(problem);
  if (scene == nullptr || scene->mRootNode == nullptr) {
    return fail(printable(importer.GetErrorString()) +
                " (OBJ, glTF/GLB, FBX and PLY are supported; re-export the file)");
  }
  return scene;
}

}  // namespace scene
