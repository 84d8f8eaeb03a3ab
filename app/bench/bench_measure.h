// Measuring one configuration for the sweeps of `aquarelle bench`: the time of one node inside
// a graph, the graph's output, and the error of that output against a reference image.
#pragma once

#include <aquarelle/core/evaluator.h>
#include <aquarelle/core/graph.h>
#include <aquarelle/core/image.h>
#include <aquarelle/core/result.h>

#include <map>
#include <string>

#include "bench_stats.h"

namespace aq::app {

struct ErrorStats {
  double max_abs = 0;   // +inf when any compared value is not finite
  double mean_abs = 0;  // over every compared pixel and channel
  double psnr = 0;      // dB for a peak of 1; +inf when the images are equal
};

// Compares the first min(channels, 3) channels (colour, not alpha) of same-sized images.
Result<ErrorStats> compare_images(const ImageF& got, const ImageF& reference);

// `image` resampled to width x height by bilinear interpolation at the new pixel centres, as a
// shader sampling it with GL_LINEAR sees it: wrapping around (a tileable texture, GL_REPEAT) or
// clamped at the borders.
ImageF resample_bilinear(const ImageF& image, int width, int height, bool periodic);

struct NodeMeasurement {
  Spread wall_ms;  // of `node_id`'s process(), glFinish before and after (holds its GPU work)
  Spread gpu_ms;   // its GL_TIMESTAMP pair (llvmpipe underestimates single draws)
  ImageF output;   // the graph's output
};

// Evaluates `graph` at its first frame warmup + frames times with outputs released after use,
// so `node_id` really runs every time. The output is read back from the last evaluation.
Result<NodeMeasurement> measure_node(Evaluator& evaluator, const Graph& graph,
                                     const std::string& node_id,
                                     const std::map<std::string, ImageF>* images, int frames,
                                     int warmup);

}  // namespace aq::app
