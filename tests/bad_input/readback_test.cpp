// Reading a texture back (issue 17, item 9): `--size 16384x16384` ended in GL error 0x0502
// after a minute because one read of w*h*16 bytes overflows GLsizei. Reads now go in bands of
// rows; the band arithmetic is checked at the documented maximum, and banded reads of a small
// texture (a band limit of a few rows) must equal what was uploaded.
#include <aquarelle/core/evaluator.h>
#include <glad/gl.h>

#include <climits>

#include "bad_input/bad_input_support.h"

namespace aq::test::bad_input {
namespace {

TEST(Readback, BandsAtTheDocumentedMaximumFitAGlsizei) {
  const int side = 16384;
  for (int bytes_per_pixel : {4, 16}) {
    const int rows = readback_rows_per_band(side, bytes_per_pixel, kMaxReadbackBytes);
    ASSERT_GE(rows, 1);
    EXPECT_LE(static_cast<int64_t>(rows) * side * bytes_per_pixel, INT_MAX) << bytes_per_pixel;
  }
  EXPECT_GT(static_cast<int64_t>(side) * side * 16, INT_MAX) << "one read would overflow";
  EXPECT_EQ(readback_rows_per_band(100, 16, 10), 1) << "at least one row per band";
}

TEST(Readback, BandedReadEqualsTheUploadedPixels) {
  // Any render makes the harness's context current.
  ASSERT_TRUE(run_node("tint", {{"image", constant_image(4, 4, 0, 0, 0)}}).ok());
  const int w = 37, h = 23;
  ImageF source = random_image(w, h, 17, -2.0f, 2.0f);
  GLuint texture = 0;
  glCreateTextures(GL_TEXTURE_2D, 1, &texture);
  glTextureStorage2D(texture, 1, GL_RGBA32F, w, h);
  glTextureSubImage2D(texture, 0, 0, 0, w, h, GL_RGBA, GL_FLOAT, source.pixels.data());
  for (int64_t limit : {int64_t{1}, int64_t{w} * 16 * 5, kMaxReadbackBytes}) {
    auto read = read_texture(texture, w, h, AQ_FORMAT_RGBA32F, limit);
    ASSERT_TRUE(read.ok()) << read.message();
    EXPECT_EQ(read->pixels, source.pixels) << "band limit " << limit;
  }
  glDeleteTextures(1, &texture);
}

}  // namespace
}  // namespace aq::test::bad_input
