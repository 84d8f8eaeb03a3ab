// The viewer's pan and zoom without GL or ImGui: where the image sits in the viewer's area, and
// which pixel lies under a point. Fit centres the whole image; the wheel zooms around the
// cursor (the pixel under it stays put); a drag pans.
#pragma once

#include <algorithm>
#include <cmath>

namespace aq::editor {

struct ImageView {
  bool fit = true;
  float zoom = 1.0f;  // screen pixels per image pixel
  float pan_x = 0;    // image's top-left, relative to the area's top-left
  float pan_y = 0;
  static constexpr float kMinZoom = 1.0f / 64.0f;
  static constexpr float kMaxZoom = 64.0f;

  // Recomputes zoom and pan when fitting.
  void place(float image_w, float image_h, float area_w, float area_h) {
    if (!fit) return;
    zoom = std::max(std::min(area_w / image_w, area_h / image_h), kMinZoom);
    pan_x = (area_w - image_w * zoom) * 0.5f;
    pan_y = (area_h - image_h * zoom) * 0.5f;
  }
  // Zoom to `new_zoom` keeping the image point under (x, y) (area coordinates) where it is.
  void zoom_to(float x, float y, float new_zoom) {
    new_zoom = std::clamp(new_zoom, kMinZoom, kMaxZoom);
    const float ix = (x - pan_x) / zoom;
    const float iy = (y - pan_y) / zoom;
    zoom = new_zoom;
    pan_x = x - ix * zoom;
    pan_y = y - iy * zoom;
    fit = false;
  }
  void pan_by(float dx, float dy) {
    pan_x += dx;
    pan_y += dy;
    fit = false;
  }
  // Image pixel (x right, y down from the top row) under area point (x, y).
  void pixel_at(float x, float y, float* ix, float* iy) const {
    *ix = std::floor((x - pan_x) / zoom);
    *iy = std::floor((y - pan_y) / zoom);
  }
};

}  // namespace aq::editor
