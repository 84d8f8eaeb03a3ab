// The viewer's evaluation policy with a real evaluator (an inline worker on one headless
// context): drafts (quality draft, a quarter of the size) only during a drag of a graph slower
// than the drag needs, the full image as soon as the drag ends, a typed value in full at once;
// moving a node or adding an unconnected one evaluates nothing; an error keeps the last image.
#include "editor/viewer.h"
#include "editor/viewer_fixture.h"

#include <aquarelle/core/gl_context.h>
#include <gtest/gtest.h>

#include "support/harness.h"

namespace aq::editor {
namespace {

using Fixture = test::ViewerFixture;

// The budget is set rather than measured so the test does not depend on the machine's speed.
TEST(Viewer, DraftsOnlyWhileDraggingASlowGraphAndRefineWhenTheDragEnds) {
  Fixture f;
  ASSERT_TRUE(f.open("graphs/underwater.json", 128, 72));
  f.viewer->set_gesture_budget_ms(0.0);  // every evaluation is slower than a drag needs
  f.viewer->update(f.state);
  ASSERT_TRUE(f.viewer->has_image()) << f.viewer->error();
  EXPECT_FALSE(f.viewer->showing_draft()) << "the first evaluation is at the graph's quality";

  // A slider drag: each step is shown as a draft.
  ASSERT_TRUE(f.document.set_param("tint", "amount", 0.3, "param:tint.amount").ok());
  f.viewer->update(f.state);
  EXPECT_TRUE(f.viewer->showing_draft());
  // The drag ends: the full image at once, no waiting for a pause.
  f.document.end_gesture();
  f.viewer->update(f.state);
  EXPECT_FALSE(f.viewer->showing_draft()) << "refined as soon as the drag ended";

  // A typed value (no gesture) is evaluated in full straight away.
  ASSERT_TRUE(f.document.set_param("tint", "amount", 0.5).ok());
  f.viewer->update(f.state);
  EXPECT_FALSE(f.viewer->showing_draft());
}

TEST(Viewer, AFastGraphIsNeverShownAsADraft) {
  Fixture f;
  ASSERT_TRUE(f.open("graphs/tint.json", 32, 32));
  f.viewer->set_gesture_budget_ms(1e9);  // every evaluation keeps up
  f.viewer->update(f.state);
  ASSERT_TRUE(f.viewer->has_image());
  ASSERT_TRUE(f.document.set_param("tint", "amount", 0.3, "param:tint.amount").ok());
  f.viewer->update(f.state);
  EXPECT_FALSE(f.viewer->showing_draft());
}

TEST(Viewer, LayoutEditsAndUnconnectedNodesEvaluateNothing) {
  Fixture f;
  ASSERT_TRUE(f.open("graphs/tint.json", 32, 32));
  f.viewer->update(f.state);
  ASSERT_TRUE(f.viewer->has_image());
  const int evaluations = f.viewer->finished_count();
  const auto runs = f.viewer->run_counts();
  ASSERT_TRUE(f.document.move_nodes({{"tint", {900, 40}}}).ok());
  f.viewer->update(f.state);
  ASSERT_TRUE(f.document.add_node("vignette", {0, 600}).ok());
  f.viewer->update(f.state);
  EXPECT_EQ(f.viewer->finished_count(), evaluations) << "no evaluation was asked for";
  EXPECT_EQ(f.viewer->run_counts(), runs);
  // An edit upstream of the output does evaluate, and runs only what lies downstream of it.
  ASSERT_TRUE(f.document.set_param("tint", "amount", 0.2).ok());
  f.viewer->update(f.state);
  EXPECT_EQ(f.viewer->finished_count(), evaluations + 1);
  EXPECT_EQ(f.viewer->run_counts().at("tint"), runs.at("tint") + 1);
  EXPECT_EQ(f.viewer->run_counts().at("scene"), runs.at("scene"));
}

TEST(Viewer, AnErrorKeepsTheLastImage) {
  Fixture f;
  ASSERT_TRUE(f.open("graphs/tint.json", 32, 32));
  f.viewer->update(f.state);
  ASSERT_TRUE(f.viewer->has_image());
  // The output's input is unlinked: evaluation fails, naming the node.
  ASSERT_TRUE(f.document.unlink("tint", "image").ok());
  f.viewer->update(f.state);
  EXPECT_FALSE(f.viewer->error().empty());
  EXPECT_EQ(f.viewer->error_node(), "tint") << f.viewer->error();
  EXPECT_TRUE(f.viewer->has_image()) << "the last good image stays on screen";
}

}  // namespace
}  // namespace aq::editor
