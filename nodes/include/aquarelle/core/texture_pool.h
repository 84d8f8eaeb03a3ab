// A pool of textures keyed by (width, height, format). A texture returns to the pool when
// its last reference is released and is handed out again for the next request with the same
// key, so memory stays bounded by the graph's width, not its length.
#pragma once

#include <aquarelle/core/gl_objects.h>
#include <aquarelle/plugin.h>

#include <cstddef>
#include <map>
#include <memory>
#include <tuple>
#include <vector>

namespace aq {

struct PooledTexture;

// A shared reference to a pool texture; the texture goes back to the pool when the last
// TextureRef to it is destroyed.
using TextureRef = std::shared_ptr<PooledTexture>;

struct PooledTexture {
  aq_image image{};
  gl::Texture texture;
  uint64_t writer = 0;  // who acquired it last (TexturePool::acquire's `writer`); 0: anyone
  uint64_t serial = 0;  // which acquisition handed it out (the pool's count)
};

class TexturePool {
 public:
  TexturePool() = default;
  ~TexturePool();
  TexturePool(const TexturePool&) = delete;
  TexturePool& operator=(const TexturePool&) = delete;

  TextureRef acquire(int width, int height, uint32_t format);
  // The same, preferring the free texture `writer` (nonzero) acquired last: `kept` says whether
  // it got that one, which then still holds what the writer left in it on its last acquisition
  // (every acquisition takes the texture's writer tag, so nobody else has written it since).
  // The texture a writer acquired last is its claim: nobody else takes it, a new texture is made
  // instead, until the writer acquires another or gives its claims up (unclaim).
  TextureRef acquire(int width, int height, uint32_t format, uint64_t writer, bool* kept);
  // The writer is gone (its node was deleted): its texture is anyone's again.
  void unclaim(uint64_t writer);
  // Makes a texture handed out untagged `writer`'s claim, as if acquired with that tag (a node
  // asks to keep its outputs after it acquired them, on its first call).
  void claim(PooledTexture& texture, uint64_t writer);

  size_t live_count() const { return live_; }  // handed out, not yet returned
  size_t free_count() const;                   // waiting in the pool
  size_t peak_live_count() const { return peak_live_; }
  size_t created_count() const { return created_; }  // GL textures ever made
  size_t bytes_allocated() const { return bytes_; }  // live + free
  void reset_peak() { peak_live_ = live_; }
  // Deletes every free texture (e.g. after a resolution change).
  void trim();

 private:
  using Key = std::tuple<int, int, uint32_t>;
  void give_back(PooledTexture* texture);
  std::map<Key, std::vector<std::unique_ptr<PooledTexture>>> free_;
  std::map<uint64_t, uint64_t> claims_;  // writer -> serial of the texture it acquired last
  uint64_t serial_ = 0;
  size_t live_ = 0;
  size_t peak_live_ = 0;
  size_t created_ = 0;
  size_t bytes_ = 0;
  std::shared_ptr<bool> alive_ = std::make_shared<bool>(true);
};

size_t bytes_per_pixel(uint32_t format);
const char* format_name(uint32_t format);

}  // namespace aq
