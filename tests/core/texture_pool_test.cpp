// Making a texture leaves the GL bindings as they were: nodes acquire scratch textures and
// outputs between binding their inputs and drawing, so a pool that bound its new texture and
// then unbound it left the active unit empty, and that draw sampled nothing there. Only the
// first frame made new textures (later ones took free ones), so a frame rendered after others
// differed from the same frame rendered alone (the layered node's fast method, issue 36).
#include <gtest/gtest.h>

#include <aquarelle/core/gl_context.h>
#include <aquarelle/core/gl_objects.h>
#include <aquarelle/core/texture_pool.h>

#include <memory>

namespace aq {
namespace {

GLint bound_texture(GLuint unit) {
  glActiveTexture(GL_TEXTURE0 + unit);
  GLint name = 0;
  glGetIntegerv(GL_TEXTURE_BINDING_2D, &name);
  return name;
}

TEST(TexturePool, MakingATextureKeepsTheBoundTexturesAndTheActiveUnit) {
  auto context = create_headless_context(GlBackend::kAuto);
  ASSERT_TRUE(context.ok()) << context.message();
  (*context)->activate();
  TexturePool pool;
  TextureRef input = pool.acquire(8, 8, AQ_FORMAT_RGBA32F);
  TextureRef other = pool.acquire(4, 4, AQ_FORMAT_RGBA16F);
  glActiveTexture(GL_TEXTURE2);
  glBindTexture(GL_TEXTURE_2D, input->image.texture);
  glActiveTexture(GL_TEXTURE3);
  glBindTexture(GL_TEXTURE_2D, other->image.texture);
  const size_t made = pool.created_count();
  TextureRef fresh = pool.acquire(16, 8, AQ_FORMAT_RGBA32F);  // a size nobody freed: made now
  ASSERT_EQ(pool.created_count(), made + 1);
  GLint active = 0;
  glGetIntegerv(GL_ACTIVE_TEXTURE, &active);
  EXPECT_EQ(active, static_cast<GLint>(GL_TEXTURE3));
  EXPECT_EQ(bound_texture(3), static_cast<GLint>(other->image.texture)) << "the active unit";
  EXPECT_EQ(bound_texture(2), static_cast<GLint>(input->image.texture));
  glBindTexture(GL_TEXTURE_2D, 0);
  glActiveTexture(GL_TEXTURE2);
  glBindTexture(GL_TEXTURE_2D, 0);
  glActiveTexture(GL_TEXTURE0);
}

}  // namespace
}  // namespace aq
