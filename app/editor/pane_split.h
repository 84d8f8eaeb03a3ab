// The splitter between the canvas and the viewer/parameter column: its place as the canvas's
// share of the window's width, moved by dragging the bar between them (as in Nuke and Blender,
// where panes are resized by their borders). No GL.
#pragma once

#include <algorithm>

namespace aq::editor {

inline constexpr float kDefaultCanvasShare = 0.56f;
inline constexpr float kMinPaneShare = 0.15f;  // neither pane can be dragged shut

// The canvas's share after the splitter was dragged `dx` pixels across a `width` pixels wide
// window.
inline float split_after_drag(float share, float dx, float width) {
  if (!(width > 0)) return share;
  return std::clamp(share + dx / width, kMinPaneShare, 1.0f - kMinPaneShare);
}

}  // namespace aq::editor
