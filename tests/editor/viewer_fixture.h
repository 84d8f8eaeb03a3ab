// A viewer on a real evaluator without a window: one headless context, an inline worker, a
// document opened from the source tree at a small size. `with_compare` adds the B viewer of
// the A/B wipe on the same context.
#pragma once

#include <aquarelle/core/gl_context.h>

#include <memory>
#include <string>

#include "editor/viewer.h"
#include "support/harness.h"

namespace aq::test {

struct ViewerFixture {
  std::unique_ptr<GlContext> context;
  editor::Document document{registry()};
  editor::EditorState state{document};
  std::unique_ptr<editor::Viewer> viewer;

  bool open(const std::string& graph, int width, int height, bool with_compare = false) {
    auto made = create_headless_context(GlBackend::kAuto);
    if (!made.ok()) return false;
    context = std::move(*made);
    if (!document.open(source_path(graph)).ok()) return false;
    Settings settings = document.graph().settings;
    settings.width = width;
    settings.height = height;
    if (!document.set_settings(settings).ok()) return false;
    viewer = std::make_unique<editor::Viewer>(
        std::make_unique<editor::EvalWorker>(registry(), *context));
    if (with_compare) {
      viewer->set_compare_viewer(std::make_unique<editor::Viewer>(
          std::make_unique<editor::EvalWorker>(registry(), *context)));
    }
    return true;
  }
};

}  // namespace aq::test
