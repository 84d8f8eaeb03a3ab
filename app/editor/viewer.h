// The viewer: evaluates the graph up to the output being viewed (any node's any output) on the
// evaluation worker (eval_worker.h), keeps the last finished image on screen meanwhile with a
// progress bar over it, and shows it in an ImGui panel through a small display pass that maps it to
// 8-bit colour: colour images through the sRGB curve, depth (R32F, depth textures) as near =
// bright over the image's own range, object ids (R32UI, or an output named "id") as distinct
// hashed colours with 0 (background) black. Fit or 1:1
// zoom; the raw value under the cursor is read straight from the evaluated texture.
//
//   EditorState ─► evaluation_key changed? ─► EvalWorker::submit(graph copy, frame, output)
//                                                   │ (worker thread)
//          take_finished() ◄── texture copy ◄───────┘
//                ▼
//   display pass (mode by format) ─► RGBA8 ─► ImGui::Image (+ error text over the last image)
#pragma once

#include "editor_state.h"
#include "eval_policy.h"
#include "eval_worker.h"
#include "image_stats.h"
#include "image_view.h"

#include <aquarelle/core/evaluator.h>
#include <aquarelle/core/gl_context.h>
#include <aquarelle/core/gl_objects.h>
#include <aquarelle/core/registry.h>
#include <imgui.h>

#include <chrono>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace aq::editor {

class Viewer {
 public:
  explicit Viewer(std::unique_ptr<EvalWorker> worker);
  ~Viewer();

  // Takes a finished evaluation, then asks for a new one when what the image depends on
  // (evaluation_key: the nodes upstream of the output, settings), the frame or the quality
  // changed (or when `force`). Never waits for the GPU.
  void update(const EditorState& state, bool force = false);
  // Draws the viewer panel's content (toolbar, image, pixel probe) into the current window.
  void draw(EditorState& state);

  // Drop the evaluator's caches (shader reload) / read shaders from their sources.
  void clear_caches() {
    worker_->clear_caches();
    if (compare_) compare_->clear_caches();
  }
  void set_shader_hot_reload(bool enabled) {
    worker_->set_shader_hot_reload(enabled);
    if (compare_) compare_->set_shader_hot_reload(enabled);
  }
  // An evaluation waits or runs (for A, or for B while comparing).
  bool busy() const { return worker_->busy() || (comparing_ && compare_->busy()); }
  // Nothing runs, nothing waits to be shown and nothing needs asking: the image is current
  // (and B's too while comparing).
  bool settled() const { return settled_ && (!comparing_ || compare_->settled()); }

  // A/B compare of two outputs: B (EditorState::compare) is evaluated by this second viewer, on
  // its own worker, kept up to date with every edit like A; the wipe shows A left of the line
  // and B right of it. Without one, only the held-picture compare is offered.
  void set_compare_viewer(std::unique_ptr<Viewer> compare) { compare_ = std::move(compare); }
  // B's viewer while comparing (nullptr otherwise), e.g. for its image and error.
  const Viewer* compare_viewer() const { return comparing_ ? compare_.get() : nullptr; }
  // B's picture (RGBA8, row 0 at the bottom), mapped with A's display settings; 0 when B has no
  // image or no compare is on.
  unsigned compare_display_texture();
  // Where the wipe line is, as a fraction of the image width (0 = all B, 1 = all A).
  void set_wipe(float at) { wipe_at_ = at < 0 ? 0 : at > 1 ? 1 : at; }
  float wipe() const { return wipe_at_; }
  // The frame of the image shown (-1: none yet).
  int shown_frame() const { return shown_frame_; }
  // Evaluations finished since the start (errors included).
  int finished_count() const { return finished_count_; }
  // Timings of the last evaluation; the canvas shows them on the nodes.
  const std::vector<NodeTiming>& timings() const { return timings_; }
  // How many times each node ran (not reused), as the worker's evaluator counts.
  const std::map<std::string, int>& run_counts() const { return run_counts_; }
  // Why the last evaluation failed ("" when it succeeded) and the node it names, if any.
  const std::string& error() const { return error_; }
  const std::string& error_node() const { return error_node_; }
  double last_evaluation_ms() const { return last_ms_; }
  // The image shown is a draft of an interactive edit, to be refined once edits pause: the
  // UI loop keeps polling instead of sleeping until then.
  bool refine_pending() const { return showing_draft_ || !settled(); }
  bool showing_draft() const { return showing_draft_; }
  // A drag of a graph whose full evaluation takes longer than this (ms) shows drafts.
  void set_gesture_budget_ms(double ms) { gesture_budget_ms_ = ms; }
  bool has_image() const { return has_image_; }
  // Keeps the picture shown now as A of the wipe compare (any output: view another one next).
  void hold_for_wipe();
  // The displayed (8-bit, mapped) picture, for the canvas backdrop; 0 when none.
  unsigned display_texture() const { return display_ ? display_.get() : 0; }
  int display_width() const { return display_width_; }
  int display_height() const { return display_height_; }
  // Whether the last frame drew the histogram plot, and what it showed.
  bool histogram_plotted() const { return histogram_plotted_; }
  const ImageStats& histogram_stats() const { return stats_; }

 private:
  void draw_toolbar(EditorState& state);
  void draw_compare_menu(EditorState& state);
  void draw_image_area(EditorState& state);
  void draw_probe(bool hovered, ImVec2 area_at, unsigned compared, float split_x);
  void draw_histogram();

  enum class Mapping { kColor = 0, kDepth = 1, kId = 2 };
  Mapping current_mapping() const;
  void render_display_texture();
  void measure_range();
  bool ensure_program();
  void take_finished();

  void draw_progress(ImVec2 at, float width) const;

  // What one evaluation was asked for; a new request goes out when the wanted one differs.
  struct Wanted {
    uint64_t key = 0;
    int frame = -1;
    int divisor = 1;
    bool draft = false;   // a proxy: "preview" or "draft" while the user drags or plays
    std::string quality;  // the proxy's quality; "" the graph's own
    std::optional<PortRef> output;
    bool operator==(const Wanted&) const = default;
  };

  std::unique_ptr<EvalWorker> worker_;
  std::unique_ptr<Viewer> compare_;       // evaluates B of the A/B compare
  bool comparing_ = false;                // EditorState::compare was set at the last update
  std::optional<PortRef> fixed_output_;   // B's viewer: the output it shows
  std::optional<Wanted> requested_;       // the last request sent
  std::map<uint64_t, Wanted> in_flight_;  // by tag
  uint64_t next_tag_ = 1;
  bool settled_ = false;
  gl::Texture shown_texture_;  // the last finished image (a copy the worker made for us)
  aq_image image_{};
  bool has_image_ = false;
  int shown_frame_ = -1;
  int finished_count_ = 0;
  std::optional<PortRef> evaluated_output_;
  std::vector<NodeTiming> timings_;
  std::map<std::string, int> run_counts_;
  std::string error_;
  std::string error_node_;
  double last_ms_ = 0;
  double last_full_ms_ = 0;  // the last evaluation at the graph's own quality
  bool showing_draft_ = false;
  bool show_histogram_ = false;  // the histogram and min/max under the toolbar
  bool stats_stale_ = true;
  unsigned stats_image_ = 0;  // the texture stats_ were read from
  ImageStats stats_;
  bool histogram_plotted_ = false;
  double last_preview_ms_ = 0;  // the last "preview" proxy's evaluation time
  double gesture_budget_ms_ = kGestureBudgetMs;

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
  ImageView view_;  // pan and zoom of the image in the viewer
  // Wipe compare: a held copy of the displayed picture (A) left of the wipe line, the live
  // image (B) right of it; or, while comparing two outputs, the viewed output (A) left and the
  // compared one (B) right.
  bool wipe_ = false;
  float wipe_at_ = 0.5f;  // fraction of the image width
  bool wipe_drag_ = false;
  gl::Texture held_;  // RGBA8 copy of display_ when "hold A" was pressed
  int held_width_ = 0;
  int held_height_ = 0;
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
