// Base colour textures for the scene plugin's meshes, read through the host (aq_host::
// read_image: OpenImageIO, OpenColorIO sRGB -> linear) once per file and shared by every mesh
// and frame that uses them. Embedded glTF textures go through a temporary file.
#pragma once

#include "mesh_data.h"
#include "model.h"

#include <aquarelle/plugin.hpp>

#include <map>
#include <memory>
#include <string>
#include <vector>

namespace scene {

class TextureCache {
 public:
  // The image file's texture, or null with `error` set.
  std::shared_ptr<const Texture> file(const aq::Context& ctx, const std::string& path,
                                      std::string* error);
  // A model material's base colour texture; null when it has none, or (with a warning that
  // names the file and says the material's colour is used) when it cannot be read.
  std::shared_ptr<const Texture> material(const aq::Context& ctx, const Model& model,
                                          const ModelMaterial& material,
                                          std::vector<std::string>* warnings);

 private:
  std::map<std::string, std::shared_ptr<const Texture>> loaded_;
};

// Gives every mesh of `model` its material's texture (meshes without uvs stay untextured, with
// a warning when their material has a texture).
void apply_model_textures(const aq::Context& ctx, Model& model, TextureCache& cache);

}  // namespace scene
