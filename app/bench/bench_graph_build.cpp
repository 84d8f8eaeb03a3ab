// Graph and test-image helpers of the `aquarelle bench` sweeps (see bench_graph_build.h).
#include "bench_graph_build.h"

#include <aquarelle/core/graph_io.h>

#include <algorithm>
#include <cmath>
#include <cstdint>

namespace aq::app {

Graph single_node_graph(const Registry& registry, const std::string& type,
                        const nlohmann::json& params,
                        const std::map<std::string, std::string>& inputs, int width, int height,
                        const std::string& precision) {
  Graph graph;
  graph.settings.width = width;
  graph.settings.height = height;
  graph.settings.precision = precision;
  graph.settings.quality = "final";
  Node node;
  node.type = type;
  for (const auto& [name, value] : params.items()) node.params[name] = value;
  for (const auto& [port, image_name] : inputs) {
    const std::string source_id = "input_" + port;
    Node source;
    source.type = "image_input";
    source.params["name"] = image_name;
    graph.nodes[source_id] = source;
    node.inputs[port] = PortRef{source_id, "image"};
  }
  graph.nodes[kNodeUnderTest] = node;
  const NodeType* node_type = registry.find(type);
  const std::string port =
      node_type != nullptr && !node_type->outputs.empty() ? node_type->outputs[0].name : "image";
  graph.output = PortRef{kNodeUnderTest, port};
  return graph;
}

nlohmann::json graph_param(const Graph& graph, const Registry& registry, const std::string& type,
                           const std::string& param) {
  const NodeType* node_type = registry.find(type);
  if (node_type == nullptr) return nullptr;
  const ParamInfo* info = node_type->param(param);
  if (info == nullptr) return nullptr;
  const std::string id = first_node_of_type(graph, type);
  Node node;
  if (!id.empty()) node = graph.nodes.at(id);
  return param_value_or_default(node, *info);
}

double number(const nlohmann::json& value, double fallback) {
  return value.is_number() ? value.get<double>() : fallback;
}

reference::CausticsParams caustics_params_of(const Graph& graph, const Registry& registry,
                                             int resolution) {
  reference::CausticsParams p;
  p.resolution = resolution;
  p.depth = number(graph_param(graph, registry, "caustics", "depth"), p.depth);
  p.amplitude = number(graph_param(graph, registry, "caustics", "amplitude"), p.amplitude);
  p.wave_scale = static_cast<int>(
      number(graph_param(graph, registry, "caustics", "wave_scale"), p.wave_scale));
  p.speed = number(graph_param(graph, registry, "caustics", "speed"), p.speed);
  p.eta = number(graph_param(graph, registry, "caustics", "eta"), p.eta);
  p.max_intensity =
      number(graph_param(graph, registry, "caustics", "max_intensity"), p.max_intensity);
  return p;
}

std::string first_node_of_type(const Graph& graph, const std::string& type) {
  for (const auto& [id, node] : graph.nodes) {
    if (node.type == type) return id;
  }
  return {};
}

namespace {

// A well-mixed 32-bit hash of a pixel (lowbias32 by C. Wellons), as a number in [0, 1).
double pixel_hash(int x, int y) {
  uint32_t h = static_cast<uint32_t>(x) * 0x9E3779B9u ^ static_cast<uint32_t>(y) * 0x85EBCA6Bu;
  h ^= h >> 16;
  h *= 0x7FEB352Du;
  h ^= h >> 15;
  h *= 0x846CA68Bu;
  h ^= h >> 16;
  return static_cast<double>(h >> 8) / 16777216.0;
}

}  // namespace

ImageF sweep_test_image(int width, int height) {
  ImageF image(width, height, 4, 1.0f);
  const double pi = 3.14159265358979323846;
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) {
      const double u = (x + 0.5) / width, v = (y + 0.5) / height;
      // Hard-edged squares (one cell in eight) exercise edges; the rest is smooth plus noise.
      const bool square = ((x / 16) % 4 == 1) && ((y / 16) % 3 == 1);
      const double noise = pixel_hash(x, y) - 0.5;
      const double r = square ? 0.95 : 0.5 + 0.4 * std::sin(2 * pi * (1.5 * u + 0.5 * v));
      const double g = square ? 0.05 : 0.5 + 0.4 * std::cos(2 * pi * (0.7 * u - 1.3 * v));
      const double b = square ? 0.6 : 0.3 + 0.3 * u + 0.25 * noise;
      image.at(x, y, 0) = static_cast<float>(std::clamp(r + 0.1 * noise, 0.0, 1.0));
      image.at(x, y, 1) = static_cast<float>(std::clamp(g, 0.0, 1.0));
      image.at(x, y, 2) = static_cast<float>(std::clamp(b, 0.0, 1.0));
    }
  }
  return image;
}

ImageF sweep_depth_image(int width, int height) {
  ImageF image(width, height, 4, 1.0f);
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) {
      const bool near =
          std::abs(x - width / 2) < width / 8 && std::abs(y - height / 2) < height / 4;
      const double z = near ? 2.0 : 0.5 + 39.5 * (x + 0.5) / width;
      for (int c = 0; c < 4; ++c) image.at(x, y, c) = static_cast<float>(z);
    }
  }
  return image;
}

}  // namespace aq::app
