// The viewer's A/B compare of two outputs without a window (one headless context, inline
// workers): B is evaluated beside A and kept up to date by its own evaluation; an edit upstream
// of B only evaluates B again; B's picture is mapped for display; compare_with refuses an
// output that does not exist, and deleting B's node ends the compare.
#include "editor/editor_actions.h"
#include "editor/viewer.h"
#include "editor/viewer_fixture.h"

#include <aquarelle/core/gl_context.h>
#include <gtest/gtest.h>

#include <glad/gl.h>

#include "support/harness.h"

namespace aq::editor {
namespace {

struct Fixture : test::ViewerFixture {
  bool open(const std::string& graph, int width, int height) {
    return ViewerFixture::open(graph, width, height, /*with_compare=*/true);
  }
};

TEST(Compare, BIsEvaluatedBesideAAndKeptUpToDate) {
  Fixture f;
  ASSERT_TRUE(f.open("graphs/tint.json", 48, 32));
  f.state.viewed = PortRef{"light", "image"};                             // A
  ASSERT_TRUE(actions::compare_with(f.state, PortRef{"tint", "image"}));  // B
  f.viewer->update(f.state);
  ASSERT_TRUE(f.viewer->has_image()) << f.viewer->error();
  const Viewer* b = f.viewer->compare_viewer();
  ASSERT_NE(b, nullptr);
  ASSERT_TRUE(b->has_image()) << b->error();
  f.viewer->update(f.state);  // nothing changed: nothing asked, A and B are current
  EXPECT_TRUE(f.viewer->settled());
  const int a_evaluations = f.viewer->finished_count();
  const int b_evaluations = b->finished_count();

  // An edit downstream of A but upstream of B: B evaluates again, A does not.
  ASSERT_TRUE(f.document.set_param("tint", "amount", 0.2).ok());
  f.viewer->update(f.state);
  EXPECT_EQ(b->finished_count(), b_evaluations + 1) << "B follows the edit";
  EXPECT_EQ(f.viewer->finished_count(), a_evaluations) << "A does not depend on tint";
  // An edit upstream of both: both evaluate again.
  ASSERT_TRUE(f.document.set_param("light", "levels", 3).ok());
  f.viewer->update(f.state);
  EXPECT_EQ(b->finished_count(), b_evaluations + 2);
  EXPECT_EQ(f.viewer->finished_count(), a_evaluations + 1);

  // B's picture, mapped for display at the image's size: the tinted image is not black.
  const unsigned texture = f.viewer->compare_display_texture();
  ASSERT_NE(texture, 0u);
  std::vector<uint8_t> pixels(48 * 32 * 4);
  glGetTextureImage(texture, 0, GL_RGBA, GL_UNSIGNED_BYTE, static_cast<GLsizei>(pixels.size()),
                    pixels.data());
  int lit = 0;
  for (size_t i = 0; i < pixels.size(); i += 4)
    lit += pixels[i] + pixels[i + 1] + pixels[i + 2] > 30;
  EXPECT_GT(lit, 48 * 32 / 2) << "most of the underwater picture is lit";

  // Compare off: B is no longer evaluated or waited for.
  ASSERT_TRUE(actions::compare_with(f.state, std::nullopt));
  f.viewer->update(f.state);
  EXPECT_EQ(f.viewer->compare_viewer(), nullptr);
  EXPECT_EQ(f.viewer->compare_display_texture(), 0u);
}

TEST(Compare, RefusesAnUnknownOutputAndEndsWhenBsNodeIsDeleted) {
  Document document{test::registry()};
  EditorState state{document};
  ASSERT_TRUE(document.open(test::source_path("graphs/tint.json")).ok());
  EXPECT_FALSE(actions::compare_with(state, PortRef{"nosuch", "image"}));
  EXPECT_FALSE(actions::compare_with(state, PortRef{"light", "nosuch"}));
  EXPECT_FALSE(state.compare);
  ASSERT_TRUE(actions::compare_with(state, PortRef{"light", "plain"}));
  EXPECT_EQ(state.compare, (PortRef{"light", "plain"}));
  EXPECT_NE(state.status.find("B light.plain"), std::string::npos) << state.status;
  ASSERT_TRUE(actions::delete_nodes(state, {"light"}));
  EXPECT_FALSE(state.compare) << "B's node is gone";
}

}  // namespace
}  // namespace aq::editor
