// One configuration's time and error for the sweeps of `aquarelle bench` (see bench_measure.h).
#include "bench_measure.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

namespace aq::app {

ImageF resample_bilinear(const ImageF& image, int width, int height, bool periodic) {
  ImageF out(width, height, image.channels, 1.0f);
  auto index = [periodic](int i, int n) {
    return periodic ? ((i % n) + n) % n : std::clamp(i, 0, n - 1);
  };
  for (int y = 0; y < height; ++y) {
    const double v = (y + 0.5) * image.height / height - 0.5;
    const int y0 = static_cast<int>(std::floor(v));
    const double ty = v - y0;
    const int ya = index(y0, image.height), yb = index(y0 + 1, image.height);
    for (int x = 0; x < width; ++x) {
      const double u = (x + 0.5) * image.width / width - 0.5;
      const int x0 = static_cast<int>(std::floor(u));
      const double tx = u - x0;
      const int xa = index(x0, image.width), xb = index(x0 + 1, image.width);
      for (int c = 0; c < image.channels; ++c) {
        const double bottom =
            image.at(xa, ya, c) + (image.at(xb, ya, c) - image.at(xa, ya, c)) * tx;
        const double top = image.at(xa, yb, c) + (image.at(xb, yb, c) - image.at(xa, yb, c)) * tx;
        out.at(x, y, c) = static_cast<float>(bottom + (top - bottom) * ty);
      }
    }
  }
  return out;
}

Result<ErrorStats> compare_images(const ImageF& got, const ImageF& reference) {
  if (got.width != reference.width || got.height != reference.height) {
    return make_error("output is " + std::to_string(got.width) + "x" + std::to_string(got.height) +
                      " but the reference is " + std::to_string(reference.width) + "x" +
                      std::to_string(reference.height));
  }
  const int channels = std::min({got.channels, reference.channels, 3});
  double max_abs = 0, sum_abs = 0, sum_squared = 0;
  bool finite = true;
  for (int y = 0; y < got.height; ++y) {
    for (int x = 0; x < got.width; ++x) {
      for (int c = 0; c < channels; ++c) {
        const double d = std::abs(double(got.at(x, y, c)) - double(reference.at(x, y, c)));
        if (!std::isfinite(d)) {
          finite = false;
          continue;
        }
        max_abs = std::max(max_abs, d);
        sum_abs += d;
        sum_squared += d * d;
      }
    }
  }
  const double count = double(got.width) * got.height * channels;
  const double infinity = std::numeric_limits<double>::infinity();
  ErrorStats stats;
  stats.max_abs = finite ? max_abs : infinity;
  stats.mean_abs = finite ? sum_abs / count : infinity;
  const double mse = sum_squared / count;
  stats.psnr = !finite ? 0.0 : mse > 0 ? 10.0 * std::log10(1.0 / mse) : infinity;
  return stats;
}

Result<NodeMeasurement> measure_node(Evaluator& evaluator, const Graph& graph,
                                     const std::string& node_id,
                                     const std::map<std::string, ImageF>* images, int frames,
                                     int warmup) {
  NodeMeasurement measurement;
  std::vector<double> gpu, cpu;
  for (int i = 0; i < warmup + std::max(frames, 1); ++i) {
    EvalOptions options;
    options.frame = graph.settings.first_frame;
    options.retain_outputs = false;
    options.retain_static_outputs = false;  // the node under test may be static: re-run it
    options.measure_gpu_time = true;
    options.finish_each_node = true;
    options.images = images;
    auto result = evaluator.evaluate(graph, options);
    if (!result.ok()) return result.error();
    if (i < warmup) continue;
    for (const auto& t : evaluator.last_timings()) {
      if (t.node != node_id) continue;
      gpu.push_back(t.gpu_ms);
      cpu.push_back(t.cpu_ms);
    }
    if (i + 1 == warmup + std::max(frames, 1)) {
      auto pixels = evaluator.read_back(*result);
      if (!pixels.ok()) return pixels.error();
      measurement.output = std::move(*pixels);
    }
  }
  measurement.gpu_ms = summarize(gpu);
  measurement.wall_ms = summarize(cpu);
  return measurement;
}

}  // namespace aq::app
