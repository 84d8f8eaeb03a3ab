// The viewer: evaluates the graph up to the output being viewed (any node's any output), keeps
// the result, and shows it in an ImGui panel through a small display pass that maps it to
// 8-bit colour: colour images through the sRGB curve, depth (R32F, depth textures) as near =
// bright over the image's own range, object ids (R32UI, or an output named "id") as distinct
// hashed colours with 0 (background) black. Fit or 1:1
// zoom; the raw value under the cursor is read straight from the evaluated texture.
//
//   EditorState ─► needs_evaluation? ─► Evaluator::evaluate(graph, {frame}, output)
//                                             │ TextureRef
//                                             ▼
//                               display pass (mode by format) ─► RGBA8 ─► ImGui::Image
#pragma once

#include "editor_state.h"

#include <aquarelle/core/evaluator.h>
#include <aquarelle/core/gl_context.h>
#include <aquarelle/core/gl_objects.h>
#include <aquarelle/core/registry.h>

#include <chrono>
#include <optional>
#include <string>
#include <vector>

namespace aq::editor {

class Viewer {
 public:
  Viewer(GlContext& context, const Registry& registry);
  ~Viewer();

  // Evaluates when the graph, the viewed output or the frame changed since the last time (or
  // when `force`). Cheap when nothing changed: the evaluator's cache re-runs only what lies
  // downstream of an edit.
  void update(const EditorState& state, bool force = false);
  // Draws the viewer panel's content (toolbar, image, pixel probe) into the current window.
  void draw(EditorState& state);

  Evaluator& evaluator() { return evaluator_; }
  // Timings of the last evaluation; the canvas shows them on the nodes.
  const std::vector<NodeTiming>& timings() const { return evaluator_.last_timings(); }
  // Why the last evaluation failed ("" when it succeeded) and the node it names, if any.
  const std::string& error() const { return error_; }
  const std::string& error_node() const { return error_node_; }
  double last_evaluation_ms() const { return last_ms_; }
  // The image shown is a draft of an interactive edit, to be refined once edits pause: the
  // UI loop keeps polling instead of sleeping until then.
  bool refine_pending() const { return showing_draft_; }
  // Evaluations slower than this (ms) make interactive edits show drafts (default: a 30 fps
  // UI frame).
  void set_ui_frame_budget_ms(double ms) { ui_frame_budget_ms_ = ms; }
  bool has_image() const { return result_ != nullptr; }

 private:
  enum class Mapping { kColor = 0, kDepth = 1, kId = 2 };
  Mapping current_mapping() const;
  void render_display_texture();
  void measure_range();
  bool ensure_program();

  Evaluator evaluator_;
  TextureRef result_;
  std::optional<PortRef> evaluated_output_;
  uint64_t evaluated_revision_ = 0;
  int evaluated_frame_ = -1;
  std::string error_;
  std::string error_node_;
  double last_ms_ = 0;
  // Interactive edits of a graph slower than a UI frame are evaluated as drafts.
  static constexpr std::chrono::milliseconds kRefineAfter{300};
  double ui_frame_budget_ms_ = 33.0;
  double last_full_ms_ = 0;  // the last evaluation at the graph's own quality
  bool showing_draft_ = false;
  std::chrono::steady_clock::time_point last_edit_{};

  gl::Program program_;
  gl::VertexArray vertex_array_;
  gl::Framebuffer framebuffer_;
  gl::Texture display_;
  int display_width_ = 0;
  int display_height_ = 0;
  bool display_stale_ = true;

  // View options.
  // Evaluates at 1/divisor of the graph's resolution, for live edits of big graphs on slow GPUs.
  int preview_divisor_ = 1;
  bool fit_ = true;
  bool srgb_ = true;
  int channel_ = 0;         // 0 rgb, 1 r, 2 g, 3 b, 4 a
  int mapping_choice_ = 0;  // 0 auto, 1 colour, 2 depth, 3 id
  float exposure_ = 0.0f;
  float range_[2] = {0.0f, 1.0f};  // depth mapping range, from the image unless edited
  bool range_from_image_ = true;
};

// Mapping a raw texel to display, shared with the tests' expectations: the sRGB curve
// (2.4 / 0.055) of a linear value clamped to [0, 1].
float linear_to_srgb(float linear);

}  // namespace aq::editor
