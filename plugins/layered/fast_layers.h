// The layered node's `fast` method (README "Fast method"): every layer at once, at half
// resolution, with a short list of the four nearest layers per texel; the per-object table
// (ids, mean albedo and depth) is built on the GPU by a compute pass, so nothing is read back.
// Cost: a fixed number of passes whatever the number of objects.
#pragma once

#include <aquarelle/plugin.hpp>
#include <aquarelle/sdk/gl_raii.hpp>
#include <aquarelle/sdk/static_layer.hpp>

#include <array>
#include <cmath>
#include <string>
#include <vector>

#include "layer_table.h"

namespace layered {

// What the node hands the method: the lighting and the lists parsed from its parameters, and
// the shadow layer when it made one (layered.cpp's shadow pass).
struct FastFrame {
  int w = 0, h = 0;
  double light[3] = {0, 1, 0}, half[3] = {0, 1, 0};
  double sigma = 0.0, edge_sigma = 0.0;  // output pixels, render scale applied
  bool run_edges = false, thin = false, has_paper = false, has_shadow = false;
  bool wet_default = false;
  std::vector<PaletteEntry> palette;
  std::vector<float> wet_ids;
  aq_image shadow_raw{}, shadow_blur{}, out{};
};

class FastLayers {
 public:
  // Slots of the GPU table: ids beyond this many in one frame are left out.
  static constexpr int kSlots = 4096;
  static constexpr int kMaxRadius = 63;       // Gaussian taps per side the passes hold
  static constexpr int kUnrolledRadius = 16;  // larger radii loop over a uniform

  FastLayers() = default;
  FastLayers(const FastLayers&) = delete;
  FastLayers& operator=(const FastLayers&) = delete;
  ~FastLayers();

  // The lists' resolution divisor: 4 where the abstraction's blur is wider than what the 4×4
  // average and the enlargement add (σ ≥ 2.24 px), else 2.
  static int divisor_for(double sigma);
  // σ at 1/D resolution giving σ at full size after the D x D average and the bilinear
  // enlargement: D² σl² + what those two add = σ² (0 when they blur that much already).
  static double low_sigma(double sigma, int divisor);
  // Whether the method can run these blurs at low resolution (σ ≥ 1.5 px, radii that fit).
  static bool applies(double sigma, double edge_sigma);
  // Paints into f.out; false after ctx.fail.
  bool run(aq::Context& ctx, const FastFrame& f);
  // Draws the kept (threshold, paper) texture again on the next run: the node's last call did
  // not run this method, so the paper's damage since then does not say what changed since it
  // was drawn.
  void forget_kept() { threshold_key_.fill(std::nan("")); }

 private:
  struct Targets {
    aq_image lists[4]{}, spare[4]{}, peak{}, spare_one{}, edges{}, blur_edges{}, colours{},
        overrides{}, cells{}, blocks[5]{}, threshold{}, pixels{};
  };
  bool build_table(aq::Context& ctx);
  bool colours(aq::Context& ctx, const FastFrame& f, Targets& t);
  bool segment_and_blur(aq::Context& ctx, const FastFrame& f, Targets& t);
  bool peaks_and_edges(aq::Context& ctx, const FastFrame& f, Targets& t);
  bool cells(aq::Context& ctx, const FastFrame& f, Targets& t);
  bool threshold_map(aq::Context& ctx, const FastFrame& f, Targets& t,
                     const std::array<double, 5>& drawn_with);
  static void set_threshold(aq::Context& ctx, GLuint program);
  bool composite(aq::Context& ctx, const FastFrame& f, const Targets& t);
  bool set_composite_inputs(aq::Context& ctx, const FastFrame& f, const Targets& t, GLuint p);
  bool gather(aq::Context& ctx, int mode, const aq_image& keys, const aq_image* values, int axis,
              double sigma, int radius, const aq_image* targets, int target_count);
  GLuint fragment(aq::Context& ctx, const char* name, std::string& text,
                  const aq_shader_source& main, const std::string& defines);
  std::string defines(aq::Context& ctx, const FastFrame& f) const;

  aq::gl::Buffer table_;
  GLuint table_program_ = 0;
  uint32_t generation_ = 0;
  int divisor_ = 2;  // this frame's, divisor_for(σ)
  std::string segment_text_, gather_text_[3], edges_text_, colours_text_, classes_text_,
      cells_text_, blocks_text_, threshold_text_;
  std::array<std::string, 4> composite_texts_;  // one per class (0, 1, 2, 3 or 4 layers)
  aq::KeptDepth class_depth_;                   // the composite's classes (composite())
  aq::gl::KeptTexture threshold_;               // (layered_threshold, paper height) per pixel
  std::array<double, 5> threshold_key_{};       // the parameters it was drawn with
  aq::gl::Sampler bilinear_;  // for the composite's interpolation inside agreeing cells
  std::vector<float> overrides_;
};

}  // namespace layered
