// libFuzzer target for the mesh header checks of the scene plugin (mesh_file_checks.cpp):
// PLY headers, glTF JSON and GLB containers of any bytes must be accepted or refused with a
// message, never crash, hang, throw or allocate by what they declare (scripts/fuzz.sh runs it
// under -rss_limit_mb). The first byte picks the format; the rest is the file. References
// outside a folder are checked against an empty scratch folder, so nothing is ever opened
// outside it. (That errors never quote a referenced file is tests/bad_input's to check: a
// refusal names references, which a mutation may fill with any bytes.)
#include "mesh_file_checks.h"

#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <string_view>

namespace {

const std::string& scratch_folder() {
  static const std::string folder = [] {
    auto dir = std::filesystem::temp_directory_path() / "aq_mesh_fuzz_folder";
    std::filesystem::create_directories(dir);
    return dir.string();
  }();
  return folder;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  if (size < 1) return 0;
  static const char* kFormats[] = {"ply", "gltf", "glb", "fbx"};
  const std::string ext = kFormats[data[0] % 4];
  const std::string_view bytes(reinterpret_cast<const char*>(data + 1), size - 1);
  const uint64_t budget = uint64_t{256} << 20;
  (void)scene::check_mesh_file_bytes(ext, bytes, bytes.size(), scratch_folder(), budget);
  return 0;
}
