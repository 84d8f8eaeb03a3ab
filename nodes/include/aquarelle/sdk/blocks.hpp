// Images stored in 2 x 2 blocks of packed pixels (AQ_FORMAT_RGBA8_HDR_BLOCKS, plugin.h): the
// morphology chain and the blur's separable passes read and write them through these.
#pragma once

#include <aquarelle/plugin.hpp>

namespace aq {

inline bool in_blocks(const aq_image& image) {
  return image.format == AQ_FORMAT_RGBA8_HDR_BLOCKS;
}

// Binds `blocks` (an RGBA32UI texture, read with texelFetch) to unit 0 of `program`'s u_blocks.
inline void bind_blocks(GLuint program, const aq_image& blocks, const aq_image& image) {
  glActiveTexture(GL_TEXTURE0);
  glBindTexture(GL_TEXTURE_2D, blocks.texture);
  glBindSampler(0, 0);
  glUniform1i(glGetUniformLocation(program, "u_blocks"), 0);
  glUniform2i(glGetUniformLocation(program, "u_image_size"), image.width, image.height);
}

}  // namespace aq
