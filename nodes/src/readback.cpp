// Reading textures back to the CPU (evaluator.h: read_texture), decoding the 8-bit HDR formats.
#include <aquarelle/core/evaluator.h>

#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <limits>

namespace aq {

int readback_rows_per_band(int width, int bytes_per_pixel, int64_t max_bytes) {
  const int64_t row = static_cast<int64_t>(std::max(width, 1)) * std::max(bytes_per_pixel, 1);
  return static_cast<int>(std::clamp<int64_t>(max_bytes / row, 1, std::numeric_limits<int>::max()));
}

// aquarelle/hdr8.glsl's aq_hdr8_decode on the CPU: rgb c = e² / (1 − e²), alpha as stored.
static void decode_hdr8(std::vector<float>& rgba) {
  for (size_t i = 0; i + 3 < rgba.size(); i += 4) {
    for (size_t c = 0; c < 3; ++c) {
      const float y = rgba[i + c] * rgba[i + c];
      rgba[i + c] = y / std::max(1.0f - y, 1.0f / 256.0f);
    }
  }
}

// An AQ_FORMAT_RGBA8_HDR_BLOCKS texture's pixels, decoded (plugin.h has the layout).
static Result<ImageF> read_blocks(GLuint texture, int width, int height) {
  const int blocks_x = (width + 1) / 2, blocks_y = (height + 1) / 2;
  std::vector<uint32_t> words(static_cast<size_t>(blocks_x) * blocks_y * 4);
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  glGetTextureSubImage(texture, 0, 0, 0, 0, blocks_x, blocks_y, 1, GL_RGBA_INTEGER, GL_UNSIGNED_INT,
                       static_cast<GLsizei>(words.size() * 4), words.data());
  if (glGetError() != GL_NO_ERROR) return make_error("reading a texture of 2 x 2 blocks failed");
  ImageF out(width, height, 4);
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) {
      const size_t block = (static_cast<size_t>(y / 2) * blocks_x + x / 2) * 4;
      const uint32_t word = words[block + (y % 2) * 2 + x % 2];
      for (int c = 0; c < 4; ++c)
        out.pixels[(static_cast<size_t>(y) * width + x) * 4 + c] =
            static_cast<float>((word >> (8 * c)) & 0xFFu) / 255.0f;
    }
  }
  decode_hdr8(out.pixels);
  return out;
}

Result<ImageF> read_texture(GLuint texture, int width, int height, uint32_t format,
                            int64_t max_bytes_per_read) {
  if (format == AQ_FORMAT_RGBA8_HDR_BLOCKS) {
    while (glGetError() != GL_NO_ERROR) {
    }
    return read_blocks(texture, width, height);
  }
  bool single =
      format == AQ_FORMAT_R32F || format == AQ_FORMAT_DEPTH32F || format == AQ_FORMAT_R32UI;
  const int channels = single ? 1 : 4;
  ImageF out(width, height, channels);
  while (glGetError() != GL_NO_ERROR) {
  }  // only this read's error counts below
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  const bool words = format == AQ_FORMAT_RGBA32UI;  // packed data: the words' values
  const bool ids = format == AQ_FORMAT_R32UI || words;
  const GLenum gl_format =
      words ? GL_RGBA_INTEGER
      : ids ? GL_RED_INTEGER
            : (format == AQ_FORMAT_DEPTH32F ? GL_DEPTH_COMPONENT : (single ? GL_RED : GL_RGBA));
  const GLenum gl_type = ids ? GL_UNSIGNED_INT : GL_FLOAT;
  // The buffer size of one read is a GLsizei: a 16384x16384 RGBA float image (4 GiB) does not
  // fit, so large textures are read in bands of rows, each well under 2 GiB.
  const int pixel_bytes = channels * 4;
  const int band = readback_rows_per_band(width, pixel_bytes, max_bytes_per_read);
  std::vector<uint32_t> id_rows;
  for (int y = 0; y < height; y += band) {
    const int rows = std::min(band, height - y);
    const size_t offset = static_cast<size_t>(y) * width * channels;
    const auto bytes = static_cast<GLsizei>(static_cast<int64_t>(rows) * width * pixel_bytes);
    void* target = out.pixels.data() + offset;
    if (ids) {
      id_rows.resize(static_cast<size_t>(rows) * width * channels);
      target = id_rows.data();
    }
    glGetTextureSubImage(texture, 0, 0, y, 0, width, rows, 1, gl_format, gl_type, bytes, target);
    if (ids) {
      for (size_t i = 0; i < id_rows.size(); ++i) {
        out.pixels[offset + i] = static_cast<float>(id_rows[i]);
      }
    }
  }
  if (GLenum error = glGetError(); error != GL_NO_ERROR) {
    char text[96];
    std::snprintf(text, sizeof(text), "reading the texture back failed (GL error 0x%04X)", error);
    return make_error(text);
  }
  if (format == AQ_FORMAT_RGBA8_HDR) decode_hdr8(out.pixels);
  return out;
}

}  // namespace aq
