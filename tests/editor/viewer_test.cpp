// The viewer's interactive previews: while a slow graph is being edited it evaluates drafts
// (quality draft, a quarter of the size through the proxy mechanism) and refines at the
// graph's own quality once the edits pause.
#include "editor/viewer.h"

#include <aquarelle/core/gl_context.h>
#include <gtest/gtest.h>

#include <chrono>
#include <thread>

#include "support/harness.h"

namespace aq::editor {
namespace {

// The budget is set rather than measured so the test does not depend on the machine's speed.
TEST(Viewer, InteractiveEditsOfASlowGraphShowDraftsThenRefine) {
  auto context = create_headless_context(GlBackend::kAuto);
  ASSERT_TRUE(context.ok()) << context.message();
  Document document(test::registry());
  ASSERT_TRUE(document.open(test::source_path("graphs/underwater.json")).ok());
  Settings settings = document.graph().settings;
  settings.width = 128;
  settings.height = 72;
  ASSERT_TRUE(document.set_settings(settings).ok());
  EditorState state(document);
  Viewer viewer(**context, test::registry());
  viewer.set_ui_frame_budget_ms(0.0);  // every evaluation counts as slower than a UI frame

  viewer.update(state);
  ASSERT_TRUE(viewer.has_image());
  EXPECT_FALSE(viewer.refine_pending()) << "the first evaluation is at the graph's quality";

  // A slider drag: each step is an edit and is shown as a draft.
  ASSERT_TRUE(document.set_param("tint", "amount", 0.3, "param:tint.amount").ok());
  viewer.update(state);
  EXPECT_TRUE(viewer.refine_pending());

  // No edit yet: nothing to do until the pause is long enough.
  viewer.update(state);
  EXPECT_TRUE(viewer.refine_pending());
  std::this_thread::sleep_for(std::chrono::milliseconds(350));
  viewer.update(state);
  EXPECT_FALSE(viewer.refine_pending()) << "refined at the graph's quality after the pause";
}

TEST(Viewer, AFastGraphIsNeverShownAsADraft) {
  auto context = create_headless_context(GlBackend::kAuto);
  ASSERT_TRUE(context.ok()) << context.message();
  Document document(test::registry());
  ASSERT_TRUE(document.open(test::source_path("graphs/tint.json")).ok());
  Settings settings = document.graph().settings;
  settings.width = 32;
  settings.height = 32;
  ASSERT_TRUE(document.set_settings(settings).ok());
  EditorState state(document);
  Viewer viewer(**context, test::registry());
  viewer.set_ui_frame_budget_ms(1e9);  // every evaluation fits in a UI frame
  viewer.update(state);
  ASSERT_TRUE(viewer.has_image());
  ASSERT_TRUE(document.set_param("tint", "amount", 0.3).ok());
  viewer.update(state);
  EXPECT_FALSE(viewer.refine_pending());
}

}  // namespace
}  // namespace aq::editor
