// Named layers of a multi-channel EXR (see render_layers.h).
#include "render_layers.h"

#include <filesystem>
#include <set>

namespace aq::app {

namespace {

bool is_vector_port(const std::string& port) {
  for (const char* word : {"normal", "position", "velocity", "motion"}) {
    if (port.find(word) != std::string::npos) return true;
  }
  return false;
}

}  // namespace

Result<LayerRequest> parse_layer(const std::string& text) {
  LayerRequest layer;
  std::string source = text;
  if (auto equals = text.find('='); equals != std::string::npos) {
    layer.name = text.substr(0, equals);
    source = text.substr(equals + 1);
    if (layer.name.empty() || layer.name.find_first_of(". ") != std::string::npos) {
      return make_error("--layer '" + text +
                        "': the layer name before '=' must be non-empty, without '.' or spaces");
    }
  }
  auto port = PortRef::parse(source);
  if (!port) {
    return make_error("--layer '" + text +
                      "': expected NODE.PORT or NAME=NODE.PORT, e.g. gbuf.normal");
  }
  layer.port = *port;
  if (layer.name.empty()) layer.name = port->port == "image" ? port->node : port->port;
  return layer;
}

Status check_layers(const std::vector<LayerRequest>& layers, const Graph& graph,
                    const Registry& registry) {
  std::set<std::string> names;
  for (const auto& layer : layers) {
    auto node = graph.nodes.find(layer.port.node);
    if (node == graph.nodes.end()) {
      std::string ids;
      for (const auto& [id, n] : graph.nodes) ids += (ids.empty() ? "" : ", ") + id;
      return make_error("--layer " + layer.port.str() + ": no node '" + layer.port.node +
                        "' in the graph (nodes: " + ids + ")");
    }
    const NodeType* type = registry.find(node->second.type);
    if (type == nullptr) continue;  // the graph's validation reports unknown types
    const PortInfo* output = type->output(layer.port.port);
    if (output == nullptr || output->type != AQ_PORT_IMAGE) {
      std::string ports;
      for (const auto& o : type->outputs) {
        if (o.type == AQ_PORT_IMAGE) ports += (ports.empty() ? "" : ", ") + o.name;
      }
      return make_error("--layer " + layer.port.str() + ": node '" + layer.port.node + "' (" +
                        type->name + ") has no image output '" + layer.port.port +
                        "' (image outputs: " + ports + ")");
    }
    if (layer.name == "R" || layer.name == "G" || layer.name == "B" || layer.name == "A" ||
        !names.insert(layer.name).second) {
      return make_error(
          "--layer " + layer.port.str() + ": the layer name '" + layer.name +
          "' is already taken; name it yourself with --layer NAME=" + layer.port.str());
    }
  }
  return Ok{};
}

std::vector<std::string> layer_channel_names(const LayerRequest& layer, int channels) {
  const std::string& n = layer.name;
  if (channels == 1) {
    const bool depth = layer.port.port.find("depth") != std::string::npos;
    return {n + (depth ? ".Z" : ".Y")};
  }
  if (is_vector_port(layer.port.port)) return {n + ".X", n + ".Y", n + ".Z"};
  return {n + ".R", n + ".G", n + ".B", n + ".A"};
}

std::string layers_path(const std::string& frame_path) {
  std::filesystem::path path(frame_path);
  std::string ext = path.extension().string();
  for (auto& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  if (ext == ".exr") return frame_path;
  return path.replace_extension(".layers.exr").string();
}

Status write_layers(Evaluator& evaluator, const Graph& graph, const EvalOptions& options,
                    const std::vector<LayerRequest>& layers, const ImageF* main,
                    const std::string& path, const WriteOptions& write_options) {
  std::vector<std::string> names;
  std::vector<ImageF> images;
  std::vector<int> used;  // channels of each image that go to the file (vectors drop alpha)
  if (main != nullptr) {
    names = {"R", "G", "B", "A"};
    images.push_back(*main);
    used.push_back(4);
  }
  for (const auto& layer : layers) {
    auto texture = evaluator.evaluate(graph, options, layer.port);
    if (!texture.ok()) {
      return make_error("--layer " + layer.port.str() + ": " + texture.message());
    }
    auto pixels = evaluator.read_back(*texture);
    if (!pixels.ok()) return make_error("--layer " + layer.port.str() + ": " + pixels.message());
    if (!images.empty() &&
        (pixels->width != images[0].width || pixels->height != images[0].height)) {
      return make_error("--layer " + layer.port.str() + ": the output is " +
                        std::to_string(pixels->width) + "x" + std::to_string(pixels->height) +
                        ", the image " + std::to_string(images[0].width) + "x" +
                        std::to_string(images[0].height) +
                        " (integer outputs are not resampled in proxy renders); render with "
                        "--quality final");
    }
    auto channel_names = layer_channel_names(layer, pixels->channels);
    names.insert(names.end(), channel_names.begin(), channel_names.end());
    used.push_back(static_cast<int>(channel_names.size()));
    images.push_back(std::move(*pixels));
  }
  if (images.empty()) return Ok{};
  const int width = images[0].width, height = images[0].height;
  ImageF all(width, height, static_cast<int>(names.size()));
  int first = 0;
  for (size_t k = 0; k < images.size(); ++k) {
    const ImageF& image = images[k];
    for (size_t i = 0; i < static_cast<size_t>(width) * height; ++i) {
      for (int c = 0; c < used[k]; ++c) {
        all.pixels[i * all.channels + first + c] = image.pixels[i * image.channels + c];
      }
    }
    first += used[k];
  }
  return write_exr_channels(path, all, names, write_options);
}

}  // namespace aq::app
