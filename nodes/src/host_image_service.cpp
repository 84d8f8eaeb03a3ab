// aq_host::read_image (see host_image_service.h): read_image() of image_io (OpenImageIO, then
// OpenColorIO from the file's colour space, sRGB for 8-bit files, to the working space), with
// its associated alpha turned back into straight alpha, which is what a texture multiplying
// an albedo and a cut-out test against a threshold need.
#include "host_image_service.h"

#include <aquarelle/core/color.h>
#include <aquarelle/core/image_io.h>

#include <algorithm>
#include <cstring>
#include <string>

namespace aq {

namespace {

int fail_with(char* error, size_t error_size, const std::string& message) {
  if (error != nullptr && error_size > 0) {
    const size_t n = std::min(message.size(), error_size - 1);
    std::memcpy(error, message.data(), n);
    error[n] = '\0';
  }
  return AQ_ERROR;
}

}  // namespace

int host_read_image(void* /*host_data*/, const char* path,
                    void (*receive)(void* user, const float* rgba, int32_t width, int32_t height),
                    void* user, char* error, size_t error_size) {
  if (path == nullptr || receive == nullptr) {
    return fail_with(error, error_size, "read_image: no path or no receiver given");
  }
  static const Result<ColorConfig> config = ColorConfig::load();
  if (!config.ok()) return fail_with(error, error_size, config.message());
  Result<ImageF> image = read_image(path, *config);
  if (!image.ok()) return fail_with(error, error_size, image.message());
  ImageF pixels = std::move(*image);
  if (pixels.channels != 4) {
    return fail_with(error, error_size, std::string("'") + path + "' did not read as RGBA");
  }
  for (size_t i = 0; i + 3 < pixels.pixels.size(); i += 4) {
    const float alpha = pixels.pixels[i + 3];
    if (alpha > 0.0f && alpha < 1.0f) {
      for (int c = 0; c < 3; ++c) pixels.pixels[i + c] /= alpha;
    }
  }
  receive(user, pixels.pixels.data(), pixels.width, pixels.height);
  return AQ_OK;
}

}  // namespace aq
