// The yardstick of `aquarelle bench`: one full-screen copy pass (a fragment shader reading one
// texel per pixel through the sampler) of the same size and format as the pipeline, timed in
// the same run. Frame costs are reported as multiples of it, which vary much less between
// machines than milliseconds do.
#pragma once

#include <aquarelle/core/gl_objects.h>
#include <aquarelle/core/result.h>

#include <cstdint>

#include "bench_stats.h"

namespace aq::app {

struct CopyPassTiming {
  // The yardstick: wall time of a batch of copies ended by glFinish, per copy. Wall time,
  // like the frame time it is compared with: on llvmpipe, GL_TIMESTAMP pairs around draws
  // that no flush separates read far too low (0.006 ms against 0.2 ms wall at 256x144).
  Spread wall_ms;
  Spread timestamp_ms;  // GL_TIMESTAMP pairs around the same batch, per copy (for reference)
};

// A copy pass ready to run: its program, textures and framebuffer. Needs a current GL 4.5
// context with the core's GL functions loaded, the same one for its whole life.
class CopyPass {
 public:
  // `format` is AQ_FORMAT_RGBA16F or AQ_FORMAT_RGBA32F.
  static Result<CopyPass> create(int width, int height, uint32_t format);

  struct Sample {
    double wall_ms = 0;       // per copy
    double timestamp_ms = 0;  // per copy
  };
  // One batch of copies between two glFinish calls; leaves the GL state as it found it
  // (nothing bound).
  Sample run_batch();

 private:
  int width_ = 0;
  int height_ = 0;
  gl::Program program_;
  gl::Texture source_;
  gl::Texture target_;
  gl::Framebuffer into_target_;  // reads source_
  gl::Framebuffer into_source_;  // reads target_
  gl::VertexArray vertex_array_;
  gl::Query start_;
  gl::Query end_;
};

}  // namespace aq::app
