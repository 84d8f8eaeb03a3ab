// Headless tests of `pigment_canvas` and `pigment_apply`, the two halves of `pigment` the host
// can fuse: together they match the double-precision reference (reference/pigment.h) within the
// bound of the 8-bit density image; the canvas is kept while its view, size, parameters and
// connected images stay (the host's input keys), and recomputed when any of them changes.
#include <gtest/gtest.h>

#include <aquarelle/core/evaluator.h>
#include <aquarelle/core/gl_context.h>

#include "aquarelle/reference/pigment.h"
#include "support/harness.h"

#include <cmath>
#include <string>

namespace {

using aq::ImageF;

// Density n is stored as n + 0.5 in 8 bits (the canvas's output, read through an
// AQ_PORT_8BIT_ENOUGH input): |Δn| ≤ 1/510, |ΔC'| ≤ C(1 − C)·w·|Δn| ≤ w/2040 per density, and
// a later density scales an earlier error by |∂C''/∂C'| = |1 − (1 − 2C')k| ≤ 1 + |k| ≤ 2.
double density_bound(double turbulence, double grain, double paper) {
  return (4.0 * turbulence + 2.0 * grain + paper) / 2040.0 + 1e-5;
}

std::string canvas_apply_graph(const nlohmann::json& canvas_inputs, const nlohmann::json& weights) {
  nlohmann::json canvas = {
      {"type", "pigment_canvas"},
      {"params",
       {{"turbulence_frequency", 3.0}, {"grain_frequency", 32.0}, {"paper_frequency", 8.0}}}};
  if (!canvas_inputs.empty()) canvas["inputs"] = canvas_inputs;
  nlohmann::json g = {
      {"aquarelle", 1},
      {"nodes",
       {{"input", {{"type", "image_input"}, {"params", {{"name", "image"}}}}},
        {"turbulence", {{"type", "image_input"}, {"params", {{"name", "turbulence"}}}}},
        {"grain", {{"type", "image_input"}, {"params", {{"name", "grain"}}}}},
        {"paper", {{"type", "image_input"}, {"params", {{"name", "paper"}}}}},
        {"canvas", canvas},
        {"apply",
         {{"type", "pigment_apply"},
          {"params", weights},
          {"inputs", {{"image", "input.image"}, {"density", "canvas.density"}}}}}}},
      {"output", "apply.image"}};
  return g.dump();
}

aq::test::RenderOptions float_options(int width, int height) {
  aq::test::RenderOptions options;
  options.width = width;
  options.height = height;
  options.precision = "float";
  return options;
}

TEST(PigmentCanvas, ProceduralCanvasAndApplyMatchTheReference) {
  const ImageF input = aq::test::random_image(64, 64, 10);
  auto out = aq::test::render_graph(canvas_apply_graph({}, nlohmann::json::object()),
                                    float_options(64, 64), {{"image", input}});
  ASSERT_TRUE(out.ok()) << out.message();
  aq::reference::PigmentParams params;
  params.frequencies = {3.0, 32.0, 8.0};
  const ImageF expected =
      aq::reference::pigment(input, {nullptr, nullptr, nullptr}, nullptr, params);
  EXPECT_GT(aq::test::max_abs_diff(expected, input), 0.03);  // the effect is visible
  // The bound holds but where the density image clips: n + 0.5 lies in [0, 1] like every density
  // image's red, so the Gaussian grain (σ = 1/6) is cut at ±3σ — 0.27 % of its cells, each moved
  // by at most w·(|n| − 0.5)/4 ≈ 0.0125 at 4.5σ — and where float and double pick neighbouring
  // Gaussian cells on a pixel centre (as for `pigment`). The clipped tails move a value by at
  // most w·(|n| − 0.5)/4 ≈ 0.0625 at 4.5σ with the default grain weight 1 (0.038 measured).
  int outside = 0;
  const double bound = density_bound(1.6, 1.0, 1.6);  // the default weights
  for (int y = 0; y < 64; ++y)
    for (int x = 0; x < 64; ++x)
      for (int c = 0; c < 3; ++c)
        outside += std::abs(double(out->at(x, y, c)) - expected.at(x, y, c)) > bound;
  EXPECT_LE(outside, 64 * 64 * 3 / 100);
  EXPECT_LE(aq::test::max_abs_diff(*out, expected, 3), 0.0625);
  EXPECT_GT(aq::test::psnr(*out, expected), 60.0);
}

TEST(PigmentCanvas, ConnectedImagesOnTheCanvasMatchTheReference) {
  const ImageF input = aq::test::random_image(64, 48, 12);
  const ImageF turbulence = aq::test::random_image(16, 16, 13);
  const ImageF grain = aq::test::random_image(64, 48, 14);
  const ImageF paper = aq::test::random_image(100, 30, 15);
  auto out = aq::test::render_graph(
      canvas_apply_graph(
          {{"turbulence", "turbulence.image"}, {"grain", "grain.image"}, {"paper", "paper.image"}},
          {{"turbulence_weight", 1.0}, {"grain_weight", 0.5}, {"paper_weight", 0.8}}),
      float_options(64, 48),
      {{"image", input}, {"turbulence", turbulence}, {"grain", grain}, {"paper", paper}});
  ASSERT_TRUE(out.ok()) << out.message();
  aq::reference::PigmentParams params;
  params.weights = {1.0, 0.5, 0.8};
  const ImageF expected =
      aq::reference::pigment(input, {&turbulence, &grain, &paper}, nullptr, params);
  EXPECT_LE(aq::test::max_abs_diff(*out, expected), density_bound(1.0, 0.5, 0.8));
  EXPECT_GT(aq::test::max_abs_diff(*out, input), 0.05);
}

// The canvas of a scene's camera, with the paper from a `noise` node of `paper_seed`.
std::string scene_canvas_graph(double yaw_target_x, int paper_seed) {
  nlohmann::json g = {
      {"aquarelle", 1},
      {"nodes",
       {{"scene",
         {{"type", "scene"},
          {"params",
           {{"preset", "cube"},
            {"camera_position", {0.0, 0.0, 5.0}},
            {"camera_target", {yaw_target_x, 0.0, 0.0}}}}}},
        {"cells",
         {{"type", "noise"}, {"params", {{"type", "worley"}, {"scale", 8}, {"seed", paper_seed}}}}},
        {"canvas",
         {{"type", "pigment_canvas"},
          {"params", {{"grain_frequency", 32.0}}},
          {"inputs", {{"scene", "scene.scene"}, {"paper", "cells.image"}}}}}}},
      {"output", "canvas.density"}};
  return g.dump();
}

// Kept frame after frame while nothing it depends on changes; a turned camera and a changed
// paper image (the paper's producer re-ran with another seed: a new input key) are drawn anew.
TEST(PigmentCanvas, KeptWhileItsViewAndImagesStayRedrawnWhenEitherChanges) {
  auto context = aq::create_headless_context(aq::GlBackend::kAuto);
  ASSERT_TRUE(context.ok()) << context.message();
  aq::Evaluator kept(**context, aq::test::registry());
  aq::Evaluator fresh(**context, aq::test::registry());
  auto render = [&](aq::Evaluator& evaluator, double target_x, int seed, bool cache, int frame) {
    auto pixels = aq::test::evaluate_text(evaluator, scene_canvas_graph(target_x, seed), frame,
                                          [cache](aq::Graph& graph) {
                                            graph.settings.width = 64;
                                            graph.settings.height = 48;
                                            graph.settings.precision = "float";
                                            graph.nodes["canvas"].params["cache"] = cache;
                                          });
    EXPECT_TRUE(pixels.ok()) << pixels.message();
    return pixels.ok() ? *pixels : ImageF();
  };
  struct Step {
    double target_x;
    int seed;
  };
  const Step steps[] = {{0.0, 3}, {0.0, 3}, {0.0, 3}, {0.6, 3}, {0.6, 3},
                        {0.6, 4}, {0.6, 4}, {0.0, 4}, {0.0, 3}};
  ImageF previous;
  int frame = 1;
  for (const Step& step : steps) {
    const ImageF a = render(kept, step.target_x, step.seed, true, frame);
    const ImageF b = render(fresh, step.target_x, step.seed, false, frame);
    ASSERT_FALSE(a.empty());
    EXPECT_LE(aq::test::max_abs_diff(a, b), 1e-6)
        << "frame " << frame << " target " << step.target_x << " paper seed " << step.seed;
    if (frame > 1 && !previous.empty() &&
        (step.target_x != steps[frame - 2].target_x || step.seed != steps[frame - 2].seed)) {
      EXPECT_GT(aq::test::max_abs_diff(a, previous), 1e-3) << "frame " << frame << " changed";
    }
    previous = a;
    ++frame;
  }
}

TEST(PigmentApply, ZeroWeightsPassThroughAndAnEmptyDensityIsAnError) {
  const ImageF input = aq::test::random_image(32, 32, 4);
  auto out = aq::test::render_graph(
      canvas_apply_graph(
          {}, {{"turbulence_weight", 0.0}, {"grain_weight", 0.0}, {"paper_weight", 0.0}}),
      float_options(32, 32), {{"image", input}});
  ASSERT_TRUE(out.ok()) << out.message();
  EXPECT_EQ(aq::test::max_abs_diff(*out, input), 0.0);
  nlohmann::json g = {
      {"aquarelle", 1},
      {"nodes",
       {{"input", {{"type", "image_input"}, {"params", {{"name", "image"}}}}},
        {"apply", {{"type", "pigment_apply"}, {"inputs", {{"image", "input.image"}}}}}}},
      {"output", "apply.image"}};
  auto missing = aq::test::render_graph(g.dump(), float_options(32, 32), {{"image", input}});
  ASSERT_FALSE(missing.ok());
  EXPECT_NE(missing.message().find("density"), std::string::npos) << missing.message();
}

}  // namespace
