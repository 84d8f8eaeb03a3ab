// `aquarelle render --layer`: node outputs written as named layers of one multi-channel EXR,
// beside the main image (in the same file when the output is .exr, else in OUT.layers.exr), so
// a compositor downstream (Nuke, Resolve, Blender) can pick passes. Channel names follow Nuke:
// `normal.X/Y/Z` for vectors, `depth.Z` for depth, `light.R/G/B/A` for colours.
#pragma once

#include <aquarelle/core/evaluator.h>
#include <aquarelle/core/graph.h>
#include <aquarelle/core/image.h>
#include <aquarelle/core/image_io.h>
#include <aquarelle/core/registry.h>
#include <aquarelle/core/result.h>

#include <string>
#include <vector>

namespace aq::app {

struct LayerRequest {
  std::string name;  // the layer's name in the file ("normal", "light")
  PortRef port;      // the node output it holds
};

// "NODE.PORT" or "NAME=NODE.PORT". Without NAME the layer is named after the port, or after the
// node when the port is the generic `image`: gbuf.normal -> normal, light.image -> light.
Result<LayerRequest> parse_layer(const std::string& text);

// Every layer names an image output of the graph, and no two layers share a name.
Status check_layers(const std::vector<LayerRequest>& layers, const Graph& graph,
                    const Registry& registry);

// The file's channel names for a layer of `channels` channels.
std::vector<std::string> layer_channel_names(const LayerRequest& layer, int channels);

// Where the layers of a frame go: the frame's own file when it is an EXR, else beside it
// (out/0001.png -> out/0001.layers.exr).
std::string layers_path(const std::string& frame_path);

// Evaluates each layer for options.frame and writes them, after `main` (RGBA, or nothing when
// the main image goes to a file of its own), into `path`.
Status write_layers(Evaluator& evaluator, const Graph& graph, const EvalOptions& options,
                    const std::vector<LayerRequest>& layers, const ImageF* main,
                    const std::string& path, const WriteOptions& write_options);

}  // namespace aq::app
