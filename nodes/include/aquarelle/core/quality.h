// Quality presets: what `settings.quality` means to the evaluator. Besides the per-node
// choices a plugin makes from aq_process_ctx::quality, a preset sets the render scale, the
// proxy mode of Nuke and the resolution percentage of Blender: nodes render at the graph's size
// times the scale and the host resamples the output back to the graph's size.
#pragma once

#include <aquarelle/core/graph.h>

#include <cstdint>
#include <string_view>

namespace aq {

// 0 draft, 1 preview, 2 final (aq_process_ctx::quality); an unknown name counts as final.
uint32_t quality_index(std::string_view quality);

// Working pixels per output pixel: final 1, preview 1/2, draft 1/4.
double render_scale(std::string_view quality);

struct PixelSize {
  int width = 0;
  int height = 0;
};

// The size nodes render at: the graph's size times the render scale, rounded, at least 1x1.
PixelSize working_size(const Settings& settings);

}  // namespace aq
