// Outputs a node gets back with their content (aq_host::output_kept, TexturePool writer tags):
// the pool hands a writer its own texture back only when nobody acquired it since, and untagged
// acquisitions leave claimed textures alone while another is free.
#include <gtest/gtest.h>

#include <aquarelle/core/texture_pool.h>

#include <memory>

#include "support/gl_context_test.h"

namespace aq {
namespace {

using KeptOutputs = test::GlContextTest;

TEST_F(KeptOutputs, AWriterGetsItsOwnTextureBackOnlyWhileNobodyTookIt) {
  TexturePool pool;
  bool kept = true;
  GLuint first = 0;
  {
    TextureRef a = pool.acquire(16, 8, AQ_FORMAT_RGBA16F, 7, &kept);
    EXPECT_FALSE(kept) << "a new texture holds nothing of the writer's";
    first = a->image.texture;
    TextureRef other = pool.acquire(16, 8, AQ_FORMAT_RGBA16F);  // someone else's, alive
  }
  // Both are free now; the writer's comes back to it, kept.
  TextureRef again = pool.acquire(16, 8, AQ_FORMAT_RGBA16F, 7, &kept);
  EXPECT_TRUE(kept);
  EXPECT_EQ(again->image.texture, first);
  again.reset();
  // An untagged acquisition takes the unclaimed texture while there is one...
  TextureRef anyone = pool.acquire(16, 8, AQ_FORMAT_RGBA16F);
  EXPECT_NE(anyone->image.texture, first);
  TextureRef writer = pool.acquire(16, 8, AQ_FORMAT_RGBA16F, 7, &kept);
  EXPECT_TRUE(kept);
  writer.reset();
  // ...and, when nothing else is free, a new one: the claimed texture stays the writer's.
  TextureRef newcomer = pool.acquire(16, 8, AQ_FORMAT_RGBA16F);
  EXPECT_NE(newcomer->image.texture, first);
  EXPECT_NE(newcomer->image.texture, anyone->image.texture);
  newcomer.reset();
  anyone.reset();
  TextureRef after = pool.acquire(16, 8, AQ_FORMAT_RGBA16F, 7, &kept);
  EXPECT_TRUE(kept);
  EXPECT_EQ(after->image.texture, first);
  // Another writer, size or format never gets it as kept.
  after.reset();
  TextureRef other_writer = pool.acquire(16, 8, AQ_FORMAT_RGBA16F, 8, &kept);
  EXPECT_FALSE(kept);
  TextureRef other_size = pool.acquire(16, 9, AQ_FORMAT_RGBA16F, 7, &kept);
  EXPECT_FALSE(kept);
}

// A writer that acquired while its texture was still held (a reader kept the last frame) claims
// the new one: the older texture, returned later, holds an older call's content and is never
// handed back as kept; and a writer that is gone (unclaim) leaves its texture to anyone.
TEST_F(KeptOutputs, OnlyTheWritersLastTextureIsKeptAndUnclaimFreesIt) {
  TexturePool pool;
  bool kept = true;
  TextureRef older = pool.acquire(16, 8, AQ_FORMAT_RGBA16F, 7, &kept);
  const GLuint older_name = older->image.texture;
  TextureRef newer = pool.acquire(16, 8, AQ_FORMAT_RGBA16F, 7, &kept);  // `older` still held
  const GLuint newer_name = newer->image.texture;
  EXPECT_FALSE(kept);
  newer.reset();
  older.reset();
  TextureRef back = pool.acquire(16, 8, AQ_FORMAT_RGBA16F, 7, &kept);
  EXPECT_TRUE(kept);
  EXPECT_EQ(back->image.texture, newer_name);
  TextureRef anyone = pool.acquire(16, 8, AQ_FORMAT_RGBA16F);
  EXPECT_EQ(anyone->image.texture, older_name) << "the older one is nobody's claim any more";
  back.reset();
  anyone.reset();
  pool.unclaim(7);
  const size_t made = pool.created_count();
  TextureRef a = pool.acquire(16, 8, AQ_FORMAT_RGBA16F);
  TextureRef b = pool.acquire(16, 8, AQ_FORMAT_RGBA16F);
  EXPECT_EQ(pool.created_count(), made) << "the unclaimed texture is reused";
}

// A node that asks to keep its outputs only after acquiring them (its first call) claims them
// then: its second call gets them back, kept.
TEST_F(KeptOutputs, AClaimAfterTheAcquisitionKeepsTheTextureForTheWriter) {
  TexturePool pool;
  bool kept = false;
  TextureRef first = pool.acquire(16, 8, AQ_FORMAT_RGBA16F, 0, &kept);
  const GLuint name = first->image.texture;
  pool.claim(*first, 9);
  first.reset();
  TextureRef anyone = pool.acquire(16, 8, AQ_FORMAT_RGBA16F);
  EXPECT_NE(anyone->image.texture, name) << "a claimed texture went to someone else";
  TextureRef second = pool.acquire(16, 8, AQ_FORMAT_RGBA16F, 9, &kept);
  EXPECT_TRUE(kept);
  EXPECT_EQ(second->image.texture, name);
}

}  // namespace
}  // namespace aq
