// The yardstick of `aquarelle bench`: one full-screen copy pass (a fragment shader reading one
// texel per pixel through the sampler) of the same size and format as the pipeline, timed in
// the same run. Frame costs are reported as multiples of it, which vary much less between
// machines than milliseconds do.
#pragma once

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

// Needs a current GL 4.5 context with the core's GL functions loaded. `format` is
// AQ_FORMAT_RGBA16F or AQ_FORMAT_RGBA32F. Runs `warmup` untimed copies first (shader
// compilation, first touch of memory), then `repetitions` timed ones.
Result<CopyPassTiming> time_copy_pass(int width, int height, uint32_t format, int repetitions,
                                      int warmup = 3);

}  // namespace aq::app
