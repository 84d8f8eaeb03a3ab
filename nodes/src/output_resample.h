// Brings the graph's output from the working size back to the graph's size when a quality
// preset renders at a reduced scale (see quality.h): one bilinear pass, the output upscale
// of a proxy render.
#pragma once

#include <aquarelle/core/gl_objects.h>
#include <aquarelle/core/result.h>
#include <aquarelle/core/texture_pool.h>

#include "shader_cache.h"

namespace aq {

class OutputResampler {
 public:
  // Returns `source` itself when it already has the size, or when its format cannot be
  // filtered (ids, depth): those stay at the working size.
  Result<TextureRef> resample(ShaderCache& shaders, TexturePool& pool, const TextureRef& source,
                              int width, int height);

 private:
  gl::Framebuffer framebuffer_;
  gl::VertexArray vertex_array_;
};

}  // namespace aq
