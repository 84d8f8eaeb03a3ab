// `read` and `image_input`: see builtin_nodes.h.
#include "builtin_nodes.h"

#include "hash.h"

#include <aquarelle/core/image_io.h>
#include <aquarelle/core/plugin_loader.h>

#include <cstdio>
#include <cstring>

namespace aq {

namespace {

NodeType read_type() {
  NodeType type;
  type.name = "read";
  type.category = "Input";
  type.description =
      "Reads an image file (any format OpenImageIO reads) and converts it to the scene-linear "
      "working space through OpenColorIO.";
  type.outputs = {PortInfo{"image", AQ_PORT_IMAGE, false, "the image, scene-linear Rec.709"}};
  ParamInfo path;
  path.name = "path";
  path.type = AQ_PARAM_PATH;
  path.ui_hint = "file";
  path.description = "image file, relative to the graph file's folder";
  ParamInfo colorspace;
  colorspace.name = "colorspace";
  colorspace.type = AQ_PARAM_STRING;
  colorspace.ui_hint = "text";
  colorspace.description = "the file's colour space; empty: from the file (sRGB for 8-bit)";
  type.params = {path, colorspace};
  type.plugin_file = "(built in)";
  return type;
}

NodeType image_input_type() {
  NodeType type;
  type.name = "image_input";
  type.category = "Input";
  type.description = "An image handed to the evaluator by the program embedding it (tests).";
  type.outputs = {PortInfo{"image", AQ_PORT_IMAGE, false, "the image as given"}};
  ParamInfo name;
  name.name = "name";
  name.type = AQ_PARAM_STRING;
  name.ui_hint = "text";
  name.description = "which of the evaluator's images to output";
  type.params = {name};
  type.plugin_file = "(built in)";
  return type;
}

}  // namespace

void register_builtin_nodes(Registry& registry) {
  std::string why;
  registry.add(read_type(), &why);
  registry.add(image_input_type(), &why);
}

TextureRef upload_image(TexturePool& pool, const ImageF& image) {
  TextureRef texture = pool.acquire(image.width, image.height, AQ_FORMAT_RGBA32F);
  std::vector<float> rgba;
  const float* data = image.pixels.data();
  if (image.channels != 4) {
    rgba.resize(static_cast<size_t>(image.width) * image.height * 4);
    for (size_t i = 0; i < static_cast<size_t>(image.width) * image.height; ++i) {
      for (int c = 0; c < 4; ++c) {
        float v = 1.0f;
        if (image.channels == 1 && c < 3) v = image.pixels[i];
        if (image.channels >= 3 && c < image.channels) v = image.pixels[i * image.channels + c];
        if (image.channels == 2 && c < 3) v = image.pixels[i * 2];
        if (image.channels == 2 && c == 3) v = image.pixels[i * 2 + 1];
        rgba[i * 4 + c] = v;
      }
    }
    data = rgba.data();
  }
  glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
  glTextureSubImage2D(texture->image.texture, 0, 0, 0, image.width, image.height, GL_RGBA, GL_FLOAT,
                      data);
  return texture;
}

uint64_t builtin_key(const NodeType& type, const std::vector<aq_param_value>& params,
                     const EvalOptions& options, uint64_t key) {
  if (type.desc != nullptr) return key;
  if (type.name == "image_input") {
    const char* name = params[0].s != nullptr ? params[0].s : "";
    if (options.images != nullptr) {
      auto it = options.images->find(name);
      if (it != options.images->end()) {
        const ImageF& image = it->second;
        key = hash_bytes(key, &image.width, sizeof(int));
        key = hash_bytes(key, &image.height, sizeof(int));
        key = hash_bytes(key, image.pixels.data(), image.pixels.size() * sizeof(float));
      }
    }
  } else if (type.name == "read") {
    std::error_code ec;
    auto time = std::filesystem::last_write_time(params[0].s != nullptr ? params[0].s : "", ec);
    auto ticks = time.time_since_epoch().count();
    key = hash_bytes(key, &ticks, sizeof(ticks));
  }
  return key;
}

int run_builtin(const NodeType& type, BuiltinState& state, const aq_process_ctx& ctx,
                const EvalOptions& options, TexturePool& pool, std::vector<TextureRef>* outputs,
                std::string* error) {
  (void)ctx;
  if (type.name == "image_input") {
    std::string name = ctx.params[0].s != nullptr ? ctx.params[0].s : "";
    if (options.images == nullptr || options.images->find(name) == options.images->end()) {
      *error = "no image named '" + name + "' was handed to the evaluator";
      return AQ_ERROR;
    }
    const ImageF& image = options.images->at(name);
    if (image.width < 1 || image.height < 1) {
      *error = "image '" + name + "' is empty";
      return AQ_ERROR;
    }
    (*outputs)[0] = upload_image(pool, image);
    return AQ_OK;
  }
  if (type.name == "read") {
    std::string path = ctx.params[0].s != nullptr ? ctx.params[0].s : "";
    std::string colorspace = ctx.params[1].s != nullptr ? ctx.params[1].s : "";
    if (path.empty()) {
      *error = "parameter 'path' is empty: set it to an image file";
      return AQ_ERROR;
    }
    static Result<ColorConfig> config = ColorConfig::load();
    if (!config.ok()) {
      *error = config.message();
      return AQ_ERROR;
    }
    ImageReadNotes notes;
    auto image = read_image(path, *config, colorspace, &notes);
    if (!image.ok()) {
      *error = "parameter 'path': " + image.message();
      return AQ_ERROR;
    }
    if (notes.non_finite_values > 0) {
      std::fprintf(stderr,
                   "warning: node '%s': parameter 'path': %s holds %zu NaN or infinite "
                   "value(s); replaced (NaN by 0, infinity by +-65504) so they cannot spread\n",
                   ctx.node_id != nullptr ? ctx.node_id : "?", path.c_str(),
                   notes.non_finite_values);
    }
    (*outputs)[0] = upload_image(pool, *image);
    state.loaded_path = path;
    return AQ_OK;
  }
  *error = "unknown built-in node type '" + type.name + "'";
  return AQ_ERROR;
}

}  // namespace aq
