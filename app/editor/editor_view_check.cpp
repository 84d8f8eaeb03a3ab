// The scripted mode's "expect_view": checks what the window shows, as drawn in the last frame,
// and puts what it found on the status line (the script's log):
//   {"do": "expect_view", "split": 0.72, "tolerance": 0.01}   the canvas's share of the width
//   {"do": "expect_view", "histogram": true}                   the viewer's plot with min/max
//   {"do": "expect_view", "document": "graph.json"}            the file the editor has open
//   {"do": "expect_view", "tooltips": {"dragging": 0, "min_hovering": 1, "min_drag_frames": 5}}
//       frames with a tooltip up while a widget is dragged / while not, and frames of dragging,
//       counted since the last such check
#include "editor_app.h"

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <stdexcept>

namespace aq::editor {

namespace {

Status check_tooltips(const nlohmann::json& wanted, int drag_frames, int dragging, int hovering) {
  if (!wanted.is_object()) throw std::invalid_argument("\"tooltips\" must be an object");
  const std::string seen = "tooltips: " + std::to_string(dragging) + " frames while dragging (" +
                           std::to_string(drag_frames) + " frames dragged), " +
                           std::to_string(hovering) + " while hovering";
  if (wanted.contains("dragging") && dragging != wanted["dragging"].get<int>()) {
    return make_error(seen);
  }
  if (hovering < wanted.value("min_hovering", 0)) return make_error(seen);
  if (drag_frames < wanted.value("min_drag_frames", 0)) return make_error(seen);
  return Ok{};
}

}  // namespace

Status EditorApp::check_view(const nlohmann::json& action) {
  std::string found;
  if (action.contains("split")) {
    if (!action["split"].is_number()) throw std::invalid_argument("\"split\" is a share 0..1");
    const double wanted = action["split"].get<double>();
    char seen[64];
    std::snprintf(seen, sizeof seen, "canvas share %.4f", canvas_share_);
    if (std::abs(canvas_share_ - wanted) > action.value("tolerance", 0.01)) {
      return make_error(std::string(seen) + ", not " + std::to_string(wanted));
    }
    found += seen;
  }
  if (action.contains("histogram")) {
    const ImageStats& stats = viewer_->histogram_stats();
    char seen[128];
    std::snprintf(seen, sizeof seen, "histogram %s: min %.6g max %.6g over %zu pixels",
                  viewer_->histogram_plotted() ? "drawn" : "not drawn", stats.min, stats.max,
                  stats.counted);
    if (viewer_->histogram_plotted() != action.value("histogram", false)) return make_error(seen);
    found += (found.empty() ? "" : "; ") + std::string(seen);
  }
  if (action.contains("document")) {
    const std::string open = std::filesystem::path(document_.path()).filename().string();
    if (open != action.value("document", std::string())) {
      return make_error("the editor has '" + document_.path() + "' open");
    }
    found += (found.empty() ? "" : "; ") + std::string("open: ") + document_.path();
  }
  if (action.contains("tooltips")) {
    Status checked = check_tooltips(action["tooltips"], view_counts_.drag_frames,
                                    view_counts_.tooltips_dragging, view_counts_.tooltips_hovering);
    view_counts_ = {};
    if (!checked) return checked;
    found += (found.empty() ? "" : "; ") + std::string("tooltips as expected");
  }
  state_.status = found;
  return Ok{};
}

}  // namespace aq::editor
