// TexturePool: textures keyed by (width, height, format), reused after their last reference.
#include <aquarelle/core/texture_pool.h>

#include <algorithm>

namespace aq {

size_t bytes_per_pixel(uint32_t format) {
  switch (format) {
    case AQ_FORMAT_RGBA16F:
      return 8;
    case AQ_FORMAT_RGBA32F:
      return 16;
    case AQ_FORMAT_R32F:
      return 4;
    case AQ_FORMAT_DEPTH32F:
      return 4;
    case AQ_FORMAT_R32UI:
      return 4;
    case AQ_FORMAT_RGBA8:
    case AQ_FORMAT_RGBA8_HDR:
    case AQ_FORMAT_RGBA8_HDR_BLOCKS:  // 16 bytes a texel of four pixels
      return 4;
    case AQ_FORMAT_RGBA32UI:
      return 16;
    default:
      return 16;
  }
}

const char* format_name(uint32_t format) {
  switch (format) {
    case AQ_FORMAT_RGBA16F:
      return "RGBA16F";
    case AQ_FORMAT_RGBA32F:
      return "RGBA32F";
    case AQ_FORMAT_R32F:
      return "R32F";
    case AQ_FORMAT_DEPTH32F:
      return "DEPTH32F";
    case AQ_FORMAT_R32UI:
      return "R32UI";
    case AQ_FORMAT_RGBA8:
      return "RGBA8";
    case AQ_FORMAT_RGBA8_HDR:
      return "RGBA8 HDR";
    case AQ_FORMAT_RGBA8_HDR_BLOCKS:
      return "RGBA8 HDR 2x2";
    case AQ_FORMAT_RGBA32UI:
      return "RGBA32UI";
    default:
      return "unknown";
  }
}

namespace {
GLenum internal_format(uint32_t format) {
  switch (format) {
    case AQ_FORMAT_RGBA16F:
      return GL_RGBA16F;
    case AQ_FORMAT_RGBA32F:
      return GL_RGBA32F;
    case AQ_FORMAT_R32F:
      return GL_R32F;
    case AQ_FORMAT_DEPTH32F:
      return GL_DEPTH_COMPONENT32F;
    case AQ_FORMAT_R32UI:
      return GL_R32UI;
    case AQ_FORMAT_RGBA8:
    case AQ_FORMAT_RGBA8_HDR:
      return GL_RGBA8;
    case AQ_FORMAT_RGBA8_HDR_BLOCKS:
    case AQ_FORMAT_RGBA32UI:
      return GL_RGBA32UI;
    default:
      return GL_RGBA32F;
  }
}
}  // namespace

TexturePool::~TexturePool() {
  *alive_ = false;
}

TextureRef TexturePool::acquire(int width, int height, uint32_t format) {
  return acquire(width, height, format, 0, nullptr);
}

TextureRef TexturePool::acquire(int width, int height, uint32_t format, uint64_t writer,
                                bool* kept) {
  Key key{width, height, format};
  std::unique_ptr<PooledTexture> texture;
  if (kept != nullptr) *kept = false;
  auto claimed = [this](const PooledTexture& t) {
    auto claim = claims_.find(t.writer);
    return t.writer != 0 && claim != claims_.end() && claim->second == t.serial;
  };
  auto it = free_.find(key);
  std::vector<std::unique_ptr<PooledTexture>>::iterator pick;
  bool found = false;
  if (it != free_.end()) {
    auto& list = it->second;
    // The writer's own claim first; else one nobody claims (a writer's texture is kept for it).
    pick = writer == 0 ? list.end() : std::find_if(list.begin(), list.end(), [&](const auto& t) {
      return t->writer == writer && claimed(*t);
    });
    if (pick != list.end()) {
      if (kept != nullptr) *kept = true;
    } else {
      pick = std::find_if(list.begin(), list.end(), [&](const auto& t) { return !claimed(*t); });
    }
    found = pick != list.end();
  }
  if (found) {
    auto& list = it->second;
    std::iter_swap(pick, list.end() - 1);
    texture = std::move(list.back());
    list.pop_back();
  } else {
    texture = std::make_unique<PooledTexture>();
    texture->texture = gl::make_texture();
    GLuint id = texture->texture.get();
    // A node may acquire after binding its inputs: the active unit's texture is put back, or
    // the node's next draw samples nothing there (the layered node's first frame did; later
    // frames took a free texture and drew right, so frames depended on the ones before).
    GLint bound = 0;
    glGetIntegerv(GL_TEXTURE_BINDING_2D, &bound);
    glBindTexture(GL_TEXTURE_2D, id);
    texture->image = aq_image{id, width, height, format};
    int32_t texels_x = 0, texels_y = 0;
    aq_image_texels(&texture->image, &texels_x, &texels_y);
    glTexStorage2D(GL_TEXTURE_2D, 1, internal_format(format), texels_x, texels_y);
    // An integer texture with a filtering sampler state is incomplete.
    bool integer = format == AQ_FORMAT_R32UI || format == AQ_FORMAT_RGBA8_HDR_BLOCKS ||
                   format == AQ_FORMAT_RGBA32UI;
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, integer ? GL_NEAREST : GL_LINEAR);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, integer ? GL_NEAREST : GL_LINEAR);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    glBindTexture(GL_TEXTURE_2D, static_cast<GLuint>(bound));
    ++created_;
    bytes_ += bytes_per_pixel(format) * static_cast<size_t>(width) * height;
  }
  texture->writer = writer;
  texture->serial = ++serial_;
  if (writer != 0) claims_[writer] = texture->serial;  // an older texture of it is anyone's now
  ++live_;
  if (live_ > peak_live_) peak_live_ = live_;
  PooledTexture* raw = texture.release();
  std::weak_ptr<bool> alive = alive_;
  return TextureRef(raw, [this, alive](PooledTexture* t) {
    auto still = alive.lock();
    if (still && *still) {
      give_back(t);
    } else {
      delete t;  // the pool is gone; the GL texture dies with it
    }
  });
}

void TexturePool::give_back(PooledTexture* texture) {
  --live_;
  const aq_image& image = texture->image;
  free_[Key{image.width, image.height, image.format}].emplace_back(texture);
}

void TexturePool::claim(PooledTexture& texture, uint64_t writer) {
  if (writer == 0) return;
  texture.writer = writer;
  claims_[writer] = texture.serial;
}

void TexturePool::unclaim(uint64_t writer) {
  if (writer != 0) claims_.erase(writer);
}

size_t TexturePool::free_count() const {
  size_t count = 0;
  for (const auto& [key, list] : free_) count += list.size();
  return count;
}

void TexturePool::trim() {
  for (auto& [key, list] : free_) {
    for (auto& texture : list) {
      bytes_ -= bytes_per_pixel(texture->image.format) * static_cast<size_t>(texture->image.width) *
                texture->image.height;
    }
    list.clear();
  }
  free_.clear();
}

}  // namespace aq
