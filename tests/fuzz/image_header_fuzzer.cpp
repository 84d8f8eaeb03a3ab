// libFuzzer target for reading images (nodes/src/image_io.cpp through OpenImageIO): any bytes
// saved as a PNG, EXR, TIFF, JPEG, HDR or BMP file must read or be refused with a message,
// never crash, hang or allocate by what a header declares; scripts/fuzz.sh runs it under
// -rss_limit_mb with AQUARELLE_MEMORY_BUDGET_MB well below that limit, so a size check that
// lets a forged header through shows up as an out-of-memory report. The first byte picks
// the extension; the rest is the file. OpenImageIO itself is not instrumented: coverage
// guides the checks around it.
#include <aquarelle/core/color.h>
#include <aquarelle/core/image_io.h>

#include <unistd.h>

#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>

namespace {

const aq::ColorConfig* config() {
  static aq::Result<aq::ColorConfig> loaded = aq::ColorConfig::load();
  if (!loaded.ok()) {
    std::fprintf(stderr, "image fuzzer: %s\n", loaded.message().c_str());
    std::abort();
  }
  return &*loaded;
}

}  // namespace

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  ::setenv("AQUARELLE_MEMORY_BUDGET_MB", "256", 0);
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  if (size < 1) return 0;
  static const char* kExtensions[] = {"png", "exr", "tif", "jpg", "hdr", "bmp"};
  static const std::string stem = (std::filesystem::temp_directory_path() /
                                   ("aq_image_fuzz_" + std::to_string(::getpid()) + "."))
                                      .string();
  const std::string path = stem + kExtensions[data[0] % 6];
  if (std::FILE* file = std::fopen(path.c_str(), "wb")) {
    std::fwrite(data + 1, 1, size - 1, file);
    std::fclose(file);
  }
  auto image = aq::read_image(path, *config());
  if (image.ok() && (image->width < 1 || image->height < 1)) std::abort();
  std::remove(path.c_str());
  return 0;
}
