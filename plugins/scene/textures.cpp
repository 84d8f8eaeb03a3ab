#include "textures.h"

#include "revision.h"

#include <unistd.h>
#include <cstdio>
#include <cstdlib>

namespace scene {

std::shared_ptr<const Texture> TextureCache::file(const aq::Context& ctx, const std::string& path,
                                                  std::string* error) {
  if (auto found = loaded_.find(path); found != loaded_.end()) return found->second;
  auto texture = std::make_shared<Texture>();
  if (!ctx.read_image(path, &texture->rgba, &texture->width, &texture->height, error)) {
    return nullptr;
  }
  texture->revision = new_revision();
  loaded_[path] = texture;
  return texture;
}

std::shared_ptr<const Texture> TextureCache::material(const aq::Context& ctx, const Model& model,
                                                      const ModelMaterial& material,
                                                      std::vector<std::string>* warnings) {
  if (material.texture.empty()) return nullptr;
  char color[64];
  std::snprintf(color, sizeof(color), "(%.3g, %.3g, %.3g)", material.color.r, material.color.g,
                material.color.b);
  const std::string stand_in = std::string("; using its colour ") + color + " untextured";
  std::string error;
  if (!material.embedded) {
    auto texture = file(ctx, material.texture, &error);
    if (!texture) {
      warnings->push_back("texture of material '" + material.name + "' in '" + model.path +
                          "': " + error + stand_in);
    }
    return texture;
  }
  const std::string key = model.path + material.texture;  // "<file>*0"
  if (auto found = loaded_.find(key); found != loaded_.end()) return found->second;
  auto embedded = model.embedded.find(material.texture);
  if (embedded == model.embedded.end()) {
    warnings->push_back("embedded texture " + material.texture + " of material '" + material.name +
                        "' in '" + model.path + "' is not in the file" + stand_in);
    return nullptr;
  }
  // The host reads files: hand it the embedded bytes as one, removed right after.
  std::string temporary = "/tmp/aquarelle-texture-XXXXXX." + embedded->second.extension;
  const int suffix = static_cast<int>(embedded->second.extension.size() + 1);
  const int fd = mkstemps(temporary.data(), suffix);
  if (fd < 0) {
    warnings->push_back("embedded texture of material '" + material.name +
                        "': no temporary file to decode it" + stand_in);
    return nullptr;
  }
  const auto& bytes = embedded->second.bytes;
  const bool written = write(fd, bytes.data(), bytes.size()) == static_cast<ssize_t>(bytes.size());
  close(fd);
  std::shared_ptr<const Texture> texture =
      written ? file(ctx, temporary, &error) : std::shared_ptr<const Texture>();
  unlink(temporary.c_str());
  loaded_.erase(temporary);
  if (!texture) {
    warnings->push_back("embedded texture " + material.texture + " of material '" + material.name +
                        "' in '" + model.path + "' could not be decoded" +
                        (error.empty() ? "" : ": " + error) + stand_in);
    return nullptr;
  }
  loaded_[key] = texture;
  return texture;
}

void apply_model_textures(const aq::Context& ctx, Model& model, TextureCache& cache) {
  for (ModelMesh& mesh : model.meshes) {
    if (mesh.material >= model.materials.size()) continue;
    const ModelMaterial& material = model.materials[mesh.material];
    if (material.texture.empty()) continue;
    if (mesh.data.uvs.empty()) {
      model.warnings.push_back("a mesh of material '" + material.name + "' in '" + model.path +
                               "' has no uvs for its texture; using its colour untextured");
      continue;
    }
    mesh.data.texture = cache.material(ctx, model, material, &model.warnings);
  }
}

}  // namespace scene
