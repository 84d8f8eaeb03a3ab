// Quality presets (see quality.h).
#include <aquarelle/core/quality.h>

#include <algorithm>
#include <cmath>

namespace aq {

uint32_t quality_index(std::string_view quality) {
  if (quality == "draft") return 0;
  if (quality == "preview") return 1;
  return 2;
}

double render_scale(std::string_view quality) {
  switch (quality_index(quality)) {
    case 0:
      return 0.25;
    case 1:
      return 0.5;
    default:
      return 1.0;
  }
}

PixelSize working_size(const Settings& settings) {
  const double scale = render_scale(settings.quality);
  auto scaled = [scale](int length) {
    return std::max(1, static_cast<int>(std::lround(length * scale)));
  };
  return PixelSize{scaled(settings.width), scaled(settings.height)};
}

}  // namespace aq
