// The layered node's per-object table: see layer_table.h.
#include "layer_table.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <sstream>

namespace layered {

bool is_object_id(float value) {
  return value >= 1.0f && value < 16777216.0f && std::floor(value) == value;
}

std::vector<Layer> collect_layers(const float* id, const float* depth, const float* albedo,
                                  size_t pixel_count, int width) {
  struct Sum {
    int x0 = 1 << 30, y0 = 1 << 30, x1 = -1, y1 = -1;
    int64_t pixels = 0;
    int64_t depth_pixels = 0;
    double depth = 0.0;
    Rgb albedo{0.0, 0.0, 0.0};
  };
  std::map<float, Sum> sums;
  for (size_t i = 0; i < pixel_count; ++i) {
    if (!is_object_id(id[i])) continue;
    Sum& s = sums[id[i]];
    ++s.pixels;
    const int x = static_cast<int>(i % static_cast<size_t>(width));
    const int y = static_cast<int>(i / static_cast<size_t>(width));
    s.x0 = std::min(s.x0, x);
    s.x1 = std::max(s.x1, x);
    s.y0 = std::min(s.y0, y);
    s.y1 = std::max(s.y1, y);
    const double z = depth[i];
    if (z > 0.0 && z < 3.0e38) {
      s.depth += z;
      ++s.depth_pixels;
    }
    for (int c = 0; c < 3; ++c) {
      const double a = albedo[4 * i + c];
      s.albedo[c] += a >= 0.0 ? std::min(a, 1.0) : 0.0;
    }
  }
  std::vector<Layer> layers;
  for (const auto& [key, s] : sums) {
    Layer layer;
    layer.id = key;
    layer.pixels = s.pixels;
    layer.x0 = s.x0;
    layer.y0 = s.y0;
    layer.x1 = s.x1;
    layer.y1 = s.y1;
    layer.mean_depth = s.depth_pixels > 0 ? s.depth / static_cast<double>(s.depth_pixels) : 0.0;
    for (int c = 0; c < 3; ++c) layer.mean_albedo[c] = s.albedo[c] / static_cast<double>(s.pixels);
    layers.push_back(layer);
  }
  std::sort(layers.begin(), layers.end(), [](const Layer& a, const Layer& b) {
    if (a.mean_depth != b.mean_depth) return a.mean_depth > b.mean_depth;
    return a.id < b.id;
  });
  return layers;
}

namespace {

std::string trim(const std::string& s) {
  const size_t a = s.find_first_not_of(" \t\n");
  if (a == std::string::npos) return "";
  return s.substr(a, s.find_last_not_of(" \t\n") - a + 1);
}

bool parse_rgb(const std::string& text, Rgb* rgb) {
  std::istringstream in(text);
  char comma1 = 0, comma2 = 0;
  Rgb v{};
  if (!(in >> v[0] >> comma1 >> v[1] >> comma2 >> v[2]) || comma1 != ',' || comma2 != ',')
    return false;
  in >> std::ws;
  if (!in.eof()) return false;
  for (double c : v)
    if (!(c >= 0.0 && c <= 1.0)) return false;
  *rgb = v;
  return true;
}

bool parse_id(const std::string& text, float* id) {
  char* end = nullptr;
  const double v = std::strtod(text.c_str(), &end);
  if (end == text.c_str() || trim(end) != "" || !is_object_id(static_cast<float>(v)) ||
      static_cast<double>(static_cast<float>(v)) != v) {
    return false;
  }
  *id = static_cast<float>(v);
  return true;
}

}  // namespace

std::string parse_palette(const std::string& text, std::vector<PaletteEntry>* entries) {
  entries->clear();
  std::istringstream in(text);
  std::string item;
  while (std::getline(in, item, ';')) {
    item = trim(item);
    if (item.empty()) continue;
    std::vector<std::string> parts;
    std::istringstream fields(item);
    std::string part;
    while (std::getline(fields, part, ':')) parts.push_back(trim(part));
    PaletteEntry entry;
    const bool ok = (parts.size() == 2 || parts.size() == 3) && parse_id(parts[0], &entry.id) &&
                    parse_rgb(parts[1], &entry.light) &&
                    (parts.size() == 2 || parse_rgb(parts[2], &entry.dark));
    if (!ok) {
      return "entry '" + item +
             "' is not ID:R,G,B or ID:R,G,B:R,G,B (an object id >= 1, then the light and "
             "optionally the dark colour, components in [0, 1]; entries separated by ';')";
    }
    entry.has_dark = parts.size() == 3;
    entries->push_back(entry);
  }
  return "";
}

std::string parse_id_list(const std::string& text, std::vector<float>* ids) {
  ids->clear();
  std::string copy = text;
  std::replace(copy.begin(), copy.end(), ',', ' ');
  std::istringstream in(copy);
  std::string token;
  while (in >> token) {
    float id = 0.0f;
    if (!parse_id(token, &id)) {
      return "'" + token +
             "' is not an object id (a whole number >= 1); separate ids with "
             "spaces or commas";
    }
    ids->push_back(id);
  }
  return "";
}

void assign_colours(std::vector<Layer>& layers, const ColourSettings& settings,
                    const std::vector<PaletteEntry>& palette,
                    const std::vector<float>& wet_in_wet_ids) {
  for (Layer& layer : layers) {
    for (int c = 0; c < 3; ++c) {
      layer.light[c] = std::pow(layer.mean_albedo[c], settings.light_density);
      layer.dark[c] = std::pow(layer.mean_albedo[c], settings.dark_density);
    }
    for (const PaletteEntry& entry : palette) {
      if (entry.id != layer.id) continue;
      layer.light = entry.light;
      if (entry.has_dark) {
        layer.dark = entry.dark;
      } else {
        // The dark wash of a given light one: the same pigment, more concentrated.
        for (int c = 0; c < 3; ++c)
          layer.dark[c] = std::pow(entry.light[c], settings.dark_density / settings.light_density);
      }
    }
    const bool listed =
        std::find(wet_in_wet_ids.begin(), wet_in_wet_ids.end(), layer.id) != wet_in_wet_ids.end();
    layer.wet_in_wet = settings.wet_in_wet_default || listed;
  }
}

}  // namespace layered
