#include "image_limits.h"

#include <aquarelle/regular_file.hpp>

namespace aq {
namespace {

// zlib's deflate reaches at most 1032:1 (258-byte matches coded in 2 bits); a little slack
// covers headers and rounding.
constexpr uint64_t kDeflateMaxRatio = 1100;

std::string megabytes(uint64_t bytes) {
  return std::to_string((bytes + (1u << 20) - 1) >> 20) + " MiB";
}

}  // namespace

uint64_t decoded_image_bytes(int w, int h, int n, int full_w, int full_h) {
  const auto area = static_cast<uint64_t>(w) * static_cast<uint64_t>(h);
  const auto shown = static_cast<uint64_t>(full_w) * static_cast<uint64_t>(full_h);
  return area * static_cast<uint64_t>(n) * sizeof(float) + shown * 4 * sizeof(float);
}

Status check_declared_size(const std::string& path, const std::string& ext, uint64_t file_bytes,
                           int w, int h, int n, int full_w, int full_h) {
  if (w <= 0 || h <= 0 || n <= 0 || full_w <= 0 || full_h <= 0) {
    return make_error("cannot read image " + path + ": its header declares no pixels");
  }
  if (ext == "png") {
    // The least a PNG of this size can decompress to: one bit per pixel plus a filter byte
    // per row (1-bit greyscale or palette).
    const uint64_t least_raw = static_cast<uint64_t>(h) * (1 + (static_cast<uint64_t>(w) + 7) / 8);
    if (least_raw > file_bytes * kDeflateMaxRatio + 65536) {
      return make_error("cannot read image " + path + ": its header declares " + std::to_string(w) +
                        "x" + std::to_string(h) +
                        " pixels, which cannot "
                        "be stored in a file of " +
                        std::to_string(file_bytes) +
                        " bytes (the header is corrupt or forged; re-export the image)");
    }
  }
  const uint64_t need = decoded_image_bytes(w, h, n, full_w, full_h);
  const uint64_t budget = files::memory_budget_bytes();
  if (need > budget) {
    return make_error("cannot read image " + path + ": decoding its " + std::to_string(w) + "x" +
                      std::to_string(h) + " pixels of " + std::to_string(n) + " channels needs " +
                      megabytes(need) + ", more than the memory budget of " + megabytes(budget) +
                      " (downscale the image, or raise AQUARELLE_MEMORY_BUDGET_MB)");
  }
  return Ok{};
}

}  // namespace aq
