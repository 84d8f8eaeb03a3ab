// Writes the colour chart of docs/pigment_chart.png (PPM on stdout, sRGB-encoded) from the CPU
// reference of pigment mixing: rows rgb, cmyk, kubelka_munk; seven pigment pairs across, each
// mixed from 0 (left) to 1 (right). Build and run from the repository root after a build:
//   g++ -std=c++20 -I tests -I nodes/include scripts/pigment_chart.cpp \
//       build/tests/libaquarelle_reference.a -o /tmp/chart && /tmp/chart > /tmp/chart.ppm &&
//   oiiotool /tmp/chart.ppm -o docs/pigment_chart.png
#include <cmath>
#include <cstdio>
#include "aquarelle/reference/pigment_mix.h"
using namespace aq::reference;
int main() {
  const auto& chart = kPigmentChart;
  const MixMode modes[] = {MixMode::kRgb, MixMode::kCmyk, MixMode::kKubelkaMunk};
  const int sw = 120, sh = 40, gap = 8, pairs = 7;
  const int W = pairs * (sw + gap) + gap, H = 3 * (sh + gap) + gap;
  std::printf("P3 %d %d 255\n", W, H);
  for (int y = 0; y < H; ++y)
    for (int x = 0; x < W; ++x) {
      Rgb c{1, 1, 1};
      const int col = (x - gap) / (sw + gap), row = (y - gap) / (sh + gap);
      const int lx = (x - gap) % (sw + gap), ly = (y - gap) % (sh + gap);
      if (x >= gap && y >= gap && col < pairs && row < 3 && lx < sw && ly < sh)
        c = mix(chart[col].a, chart[col].b, double(lx) / (sw - 1), modes[row]);
      for (double v : c) {
        v = v <= 0.0031308 ? 12.92 * v : 1.055 * std::pow(v, 1 / 2.4) - 0.055;
        std::printf("%d ", int(std::lround(255 * std::fmin(1, std::fmax(0, v)))));
      }
      std::printf("\n");
    }
}
