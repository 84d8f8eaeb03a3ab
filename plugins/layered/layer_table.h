// The per-object table of the layered node, built on the CPU from the g-buffer: which ids are
// in the frame, their mean albedo and view depth (the back-to-front order of the layers), the
// colours each layer is painted with and its wet-edge kind. Plain C++ (no GL), so the CPU
// reference and the node share nothing but this definition of the order.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

namespace layered {

using Rgb = std::array<double, 3>;

struct Layer {
  float id = 0.0f;
  int64_t pixels = 0;
  double mean_depth = 0.0;  // over the pixels with a positive finite depth; 0 when none
  Rgb mean_albedo{0.0, 0.0, 0.0};
  Rgb light{1.0, 1.0, 1.0};  // colour of the lit wash
  Rgb dark{0.0, 0.0, 0.0};   // colour of the unlit wash
  bool wet_in_wet = false;
  // Pixel bounding box of the object (inclusive), so passes can skip the rest of the image.
  int x0 = 0, y0 = 0, x1 = -1, y1 = -1;
};

// An id is a pixel value that is a whole number >= 1 (and finite, below 2^24); the rest is
// background.
bool is_object_id(float value);

// Layers of every id present, far to near (mean depth descending, then id ascending).
// `id` and `depth` hold one float per pixel, `albedo` four; rows of `width` pixels.
std::vector<Layer> collect_layers(const float* id, const float* depth, const float* albedo,
                                  size_t pixel_count, int width);

struct PaletteEntry {
  float id = 0.0f;
  Rgb light{};
  bool has_dark = false;
  Rgb dark{};
};
// Parses "ID:R,G,B[:R,G,B]; ..." (light colour, then optionally the dark one). Returns an empty
// string or what is wrong, naming the entry.
std::string parse_palette(const std::string& text, std::vector<PaletteEntry>* entries);
// Parses a list of ids separated by spaces or commas.
std::string parse_id_list(const std::string& text, std::vector<float>* ids);

struct ColourSettings {
  double light_density = 0.6;  // light = albedo^light_density
  double dark_density = 1.8;   // dark = albedo^dark_density
  bool wet_in_wet_default = false;
};
// Fills light, dark and wet_in_wet of every layer: from its mean albedo (Beer–Lambert: a wash
// of concentration c transmits albedo^c), then the palette's overrides.
void assign_colours(std::vector<Layer>& layers, const ColourSettings& settings,
                    const std::vector<PaletteEntry>& palette,
                    const std::vector<float>& wet_in_wet_ids);

}  // namespace layered
