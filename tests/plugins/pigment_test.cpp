// Headless tests of the `pigment` node against the double-precision reference
// (reference/pigment.h): density 1 is the identity, values in [0, 1] stay in [0, 1] for
// any weight, procedural and connected textures match the reference in both precisions, object
// anchoring keeps the pattern on a moving object (screen anchoring does not), and bad inputs give
// errors or finite output, never NaN.
#include <gtest/gtest.h>

#include <aquarelle/core/evaluator.h>
#include <aquarelle/core/graph_io.h>

#include "aquarelle/reference/pigment.h"
#include "plugins/watercolor_test_images.h"
#include "support/harness.h"

#include <cmath>
#include <limits>
#include <string>

namespace {

using aq::ImageF;
using aq::test::watercolor::quantized;

aq::test::RenderOptions options_for(const ImageF& image, const std::string& precision) {
  aq::test::RenderOptions options;
  options.width = image.width;
  options.height = image.height;
  options.precision = precision;
  return options;
}

// Frequencies chosen so that no Gaussian cell boundary falls on a pixel centre at 64 px
// (32 cells per image height: centres at quarter cells), keeping float and double in the same
// cells.
nlohmann::json test_params() {
  return {{"turbulence_frequency", 3.0}, {"grain_frequency", 32.0}, {"paper_frequency", 8.0}};
}
aq::reference::PigmentParams reference_params() {
  aq::reference::PigmentParams params;
  params.frequencies = {3.0, 32.0, 8.0};
  return params;
}

// Fraction of pixels whose largest channel error is at most `tolerance`.
double fraction_within(const ImageF& a, const ImageF& b, double tolerance) {
  int good = 0;
  for (int y = 0; y < a.height; ++y) {
    for (int x = 0; x < a.width; ++x) {
      double worst = 0.0;
      for (int c = 0; c < 4; ++c)
        worst = std::max(worst, std::abs(double(a.at(x, y, c)) - b.at(x, y, c)));
      good += worst <= tolerance;
    }
  }
  return static_cast<double>(good) / (a.width * a.height);
}

TEST(Pigment, ZeroWeightsPassThrough) {
  const ImageF input = aq::test::random_image(32, 32, 4);
  auto out =
      aq::test::run_node("pigment", {{"image", input}},
                         {{"turbulence_weight", 0.0}, {"grain_weight", 0.0}, {"paper_weight", 0.0}},
                         options_for(input, "float"));
  ASSERT_TRUE(out.ok()) << out.message();
  EXPECT_EQ(aq::test::max_abs_diff(*out, input), 0.0);
}

// Textures of 0.5 everywhere mean n = 0, d = 1: C(1 − (1 − C)·0) = C exactly, at full weight.
TEST(Pigment, DensityOneIsIdentity) {
  const ImageF input = quantized(aq::test::random_image(48, 32, 6));
  const ImageF neutral = aq::test::constant_image(16, 16, 0.5f, 0.5f, 0.5f, 1.0f);
  for (const char* precision : {"float", "half"}) {
    auto out = aq::test::run_node(
        "pigment",
        {{"image", input}, {"turbulence", neutral}, {"grain", neutral}, {"paper", neutral}},
        {{"turbulence_weight", 4.0}, {"grain_weight", 4.0}, {"paper_weight", 4.0}},
        options_for(input, precision));
    ASSERT_TRUE(out.ok()) << out.message();
    EXPECT_EQ(aq::test::max_abs_diff(*out, input), 0.0) << precision;
  }
}

// d is clamped to [0, 2], exactly the range for which C' stays in [0, 1] for all C in [0, 1];
// 0 and 1 are fixed points of the formula.
TEST(Pigment, KeepsValuesInZeroOne) {
  ImageF input = aq::test::random_image(64, 64, 8);
  for (int x = 0; x < 64; ++x) {
    for (int c = 0; c < 3; ++c) {
      input.at(x, 0, c) = 0.0f;
      input.at(x, 1, c) = 1.0f;
    }
  }
  const ImageF black = aq::test::constant_image(8, 8, 0.0f, 0.0f, 0.0f, 1.0f);
  const ImageF white = aq::test::constant_image(8, 8, 1.0f, 1.0f, 1.0f, 1.0f);
  const nlohmann::json strong = {
      {"turbulence_weight", 4.0}, {"grain_weight", 4.0}, {"paper_weight", 4.0}};
  std::vector<std::map<std::string, ImageF>> cases = {
      {{"image", input}},
      {{"image", input}, {"turbulence", black}, {"grain", white}, {"paper", black}},
      {{"image", input}, {"turbulence", white}, {"grain", black}, {"paper", white}}};
  for (size_t i = 0; i < cases.size(); ++i) {
    for (const char* precision : {"float", "half"}) {
      auto out = aq::test::run_node("pigment", cases[i], strong, options_for(input, precision));
      ASSERT_TRUE(out.ok()) << out.message();
      for (int y = 0; y < 64; ++y) {
        for (int x = 0; x < 64; ++x) {
          for (int c = 0; c < 3; ++c) {
            const float v = out->at(x, y, c);
            ASSERT_TRUE(v >= 0.0f && v <= 1.0f) << "case " << i << " " << precision << " " << v;
          }
        }
      }
      for (int x = 0; x < 64; ++x) {
        EXPECT_EQ(out->at(x, 0, 0), 0.0f);
        EXPECT_EQ(out->at(x, 1, 0), 1.0f);
      }
    }
  }
}

TEST(Pigment, ProceduralScreenMatchesReference) {
  const ImageF input = aq::test::random_image(64, 64, 10);
  const ImageF expected =
      aq::reference::pigment(input, {nullptr, nullptr, nullptr}, nullptr, reference_params());
  EXPECT_GT(aq::test::max_abs_diff(expected, input), 0.03);  // the effect is visible
  for (const char* precision : {"float", "half"}) {
    auto out = aq::test::run_node("pigment", {{"image", input}}, test_params(),
                                  options_for(input, precision));
    ASSERT_TRUE(out.ok()) << out.message();
    const double psnr = aq::test::psnr(*out, expected);
    const double within =
        fraction_within(*out, expected, std::string(precision) == "float" ? 1e-4 : 1e-3);
    EXPECT_GE(within, 0.999) << precision;
    EXPECT_GE(psnr, std::string(precision) == "float" ? 80.0 : 65.0) << precision;
    RecordProperty(std::string("psnr_db_") + precision, std::to_string(psnr));
    RecordProperty(std::string("max_abs_error_") + precision,
                   std::to_string(aq::test::max_abs_diff(*out, expected)));
  }
}

TEST(Pigment, ConnectedTexturesMatchReference) {
  const ImageF input = aq::test::random_image(64, 48, 12);
  const ImageF turbulence = aq::test::random_image(16, 16, 13);
  const ImageF grain = aq::test::random_image(64, 48, 14);
  const ImageF paper = aq::test::random_image(100, 30, 15);
  auto out = aq::test::run_node(
      "pigment", {{"image", input}, {"turbulence", turbulence}, {"grain", grain}, {"paper", paper}},
      {{"turbulence_weight", 1.0}, {"grain_weight", 0.5}, {"paper_weight", 0.8}},
      options_for(input, "float"));
  ASSERT_TRUE(out.ok()) << out.message();
  aq::reference::PigmentParams params;
  params.weights = {1.0, 0.5, 0.8};
  const ImageF expected =
      aq::reference::pigment(input, {&turbulence, &grain, &paper}, nullptr, params);
  EXPECT_LE(aq::test::max_abs_diff(*out, expected), 1e-5);
}

// Issue 37: paper grain is darker in the paper's valleys. A flat wash (C = 0.5) over a paper
// height image whose left half is a valley (0.2) and right half a peak (0.8): pigment settles
// in the valley (d > 1, darker than the wash) and leaves the peak lighter, as Bousseau et al.
// describe the paper's grain; with the paper weight at its default.
TEST(Pigment, PaperGrainIsDarkerInTheValleys) {
  const ImageF wash = aq::test::constant_image(64, 32, 0.5f, 0.5f, 0.5f, 1.0f);
  ImageF paper(64, 32, 4, 1.0f);
  for (int y = 0; y < 32; ++y)
    for (int x = 0; x < 64; ++x)
      for (int c = 0; c < 3; ++c) paper.at(x, y, c) = x < 32 ? 0.2f : 0.8f;
  auto out = aq::test::run_node("pigment", {{"image", wash}, {"paper", paper}},
                                {{"turbulence_weight", 0.0}, {"grain_weight", 0.0}},
                                options_for(wash, "float"));
  ASSERT_TRUE(out.ok()) << out.message();
  const float valley = out->at(8, 16, 1), peak = out->at(56, 16, 1);
  EXPECT_LT(valley, 0.5f - 0.05f) << "the valley holds more pigment";
  EXPECT_GT(peak, 0.5f + 0.05f) << "the peak holds less";
}

// HDR highlights (a caustic of 3) under a light density: the formula alone gives
// 3 (1 - (1 - 3)(d - 1)) = -3 at d = 0; only the part up to 1 is modified, the excess is kept.
TEST(Pigment, HdrHighlightsStayPositive) {
  const ImageF bright = aq::test::constant_image(16, 16, 3.0f, 1.5f, 0.5f, 1.0f);
  const ImageF peak = aq::test::constant_image(16, 16, 1.0f, 1.0f, 1.0f, 1.0f);  // d = 0
  auto out =
      aq::test::run_node("pigment", {{"image", bright}, {"paper", peak}},
                         {{"turbulence_weight", 0.0}, {"grain_weight", 0.0}, {"paper_weight", 4.0}},
                         options_for(bright, "float"));
  ASSERT_TRUE(out.ok()) << out.message();
  EXPECT_FLOAT_EQ(out->at(5, 5, 0), 3.0f) << "1 stays 1, the excess is kept";
  EXPECT_FLOAT_EQ(out->at(5, 5, 1), 1.5f);
  EXPECT_NEAR(out->at(5, 5, 2), 0.75f, 1e-6) << "0.5 (1 + 0.5) at d = 0, lighter";
}

// A flat object at world z = 0.5 over the left 3/4 of the image (background on the right).
ImageF plane_positions(int width, int height, int shift_x) {
  ImageF position(width, height, 4, 0.0f);
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) {
      const int object_x = x - shift_x;  // the object moved right by shift_x pixels
      if (object_x < 0 || object_x >= 3 * width / 4) continue;
      position.at(x, y, 0) = static_cast<float>(object_x) / 16.0f;
      position.at(x, y, 1) = static_cast<float>(y) / 16.0f;
      position.at(x, y, 2) = 0.5f;
      position.at(x, y, 3) = 1.0f;
    }
  }
  return position;
}

TEST(Pigment, ObjectAnchoringMatchesReference) {
  const ImageF input = aq::test::random_image(64, 64, 16);
  const ImageF position = plane_positions(64, 64, 0);
  nlohmann::json params = test_params();
  params["anchoring"] = "object";
  auto out = aq::test::run_node("pigment", {{"image", input}, {"position", position}}, params,
                                options_for(input, "float"));
  ASSERT_TRUE(out.ok()) << out.message();
  aq::reference::PigmentParams reference = reference_params();
  reference.object_anchoring = true;
  const ImageF expected =
      aq::reference::pigment(input, {nullptr, nullptr, nullptr}, &position, reference);
  EXPECT_GE(fraction_within(*out, expected, 1e-4), 0.995);
}

// The object (colour and world positions) moves 8 pixels right: with object anchoring its
// pigment pattern moves with it; with screen anchoring the pattern stays on the screen (the
// seed's "dirty lens" under moving objects).
TEST(Pigment, ObjectAnchoringFollowsTheObject) {
  const ImageF grey = aq::test::constant_image(64, 64, 0.5f, 0.5f, 0.5f, 1.0f);
  nlohmann::json params = test_params();
  params["paper_weight"] = 0.0;  // the paper belongs to the canvas, not to the object
  params["anchoring"] = "object";
  auto before =
      aq::test::run_node("pigment", {{"image", grey}, {"position", plane_positions(64, 64, 0)}},
                         params, options_for(grey, "float"));
  auto after =
      aq::test::run_node("pigment", {{"image", grey}, {"position", plane_positions(64, 64, 8)}},
                         params, options_for(grey, "float"));
  params["anchoring"] = "screen";
  auto screen =
      aq::test::run_node("pigment", {{"image", grey}}, params, options_for(grey, "float"));
  ASSERT_TRUE(before.ok() && after.ok() && screen.ok()) << before.message();
  double object_mismatch = 0.0;
  double screen_mismatch = 0.0;
  for (int y = 0; y < 64; ++y) {
    for (int x = 0; x < 40; ++x) {  // inside the object in both frames
      object_mismatch =
          std::max(object_mismatch, std::abs(double(after->at(x + 8, y, 0)) - before->at(x, y, 0)));
      screen_mismatch = std::max(screen_mismatch,
                                 std::abs(double(screen->at(x + 8, y, 0)) - screen->at(x, y, 0)));
    }
  }
  EXPECT_LE(object_mismatch, 1e-6);
  EXPECT_GT(screen_mismatch, 0.01);
}

// Screen anchoring with a scene: the dynamic canvas turns with the camera. Yawing the camera by
// δ = 0.125 · 2 tan(fov/2) moves the content at the centre by 1/8 of the image height (8 px at
// 64 px), and the pigment pattern must move by exactly as much.
std::string canvas_graph(double yaw) {
  const double distance = 5.0;
  nlohmann::json graph = {
      {"aquarelle", 1},
      {"settings", {{"width", 64}, {"height", 64}}},
      {"nodes",
       {{"grey", {{"type", "image_input"}, {"params", {{"name", "grey"}}}}},
        {"scene",
         {{"type", "scene"},
          {"params",
           {{"preset", "cube"},
            {"fov", 50.0},
            {"camera_position", {0.0, 0.0, distance}},
            {"camera_target",
             {distance * std::sin(yaw), 0.0, distance - distance * std::cos(yaw)}}}}}},
        {"pigment",
         {{"type", "pigment"},
          {"params", test_params()},
          {"inputs", {{"image", "grey.image"}, {"scene", "scene.scene"}}}}}}},
      {"output", "pigment.image"}};
  return graph.dump();
}

TEST(Pigment, DynamicCanvasTurnsWithTheCamera) {
  constexpr double kPi = 3.14159265358979323846;
  const ImageF grey = aq::test::constant_image(64, 64, 0.5f, 0.5f, 0.5f, 1.0f);
  const double yaw = 0.125 * 2.0 * std::tan(25.0 * kPi / 180.0);
  aq::test::RenderOptions options;
  auto ahead = aq::test::render_graph(canvas_graph(0.0), options, {{"grey", grey}});
  auto turned = aq::test::render_graph(canvas_graph(yaw), options, {{"grey", grey}});
  ASSERT_TRUE(ahead.ok()) << ahead.message();
  ASSERT_TRUE(turned.ok()) << turned.message();
  EXPECT_GT(aq::test::max_abs_diff(*ahead, *turned, 3), 0.01);  // the canvas did move
  int matching = 0;
  for (int y = 0; y < 64; ++y) {
    for (int x = 0; x < 56; ++x) {
      matching += std::abs(turned->at(x, y, 0) - ahead->at(x + 8, y, 0)) <= 1e-4;
    }
  }
  EXPECT_GE(matching, 56 * 64 * 99 / 100);
  // And the canvas matches the reference with the pan and zoom of that camera.
  aq::reference::PigmentParams params = reference_params();
  params.pan_x = 0.125;
  params.zoom = -std::log2(5.0);
  const ImageF expected =
      aq::reference::pigment(grey, {nullptr, nullptr, nullptr}, nullptr, params);
  EXPECT_GE(fraction_within(*turned, expected, 1e-4), 0.99);
}

// The procedural canvas densities are kept while the view stays (cache_canvas): frame after
// frame, and after the camera turns and turns back, the image equals the one computed afresh.
TEST(Pigment, CachedCanvasEqualsTheCanvasComputedEachFrame) {
  constexpr double kPi = 3.14159265358979323846;
  const double yaw = 0.125 * 2.0 * std::tan(25.0 * kPi / 180.0);
  std::map<std::string, ImageF> images{{"grey", aq::test::random_image(64, 64, 5, 0.0f, 1.0f)}};
  auto context = aq::create_headless_context(aq::GlBackend::kAuto);
  ASSERT_TRUE(context.ok()) << context.message();
  aq::Evaluator cached(**context, aq::test::registry());
  aq::Evaluator fresh(**context, aq::test::registry());
  auto render = [&](aq::Evaluator& evaluator, double angle, bool cache, int frame) {
    auto pixels = aq::test::evaluate_text(
        evaluator, canvas_graph(angle), frame,
        [cache](aq::Graph& graph) {
          graph.settings.precision = "float";
          graph.nodes["pigment"].params["cache_canvas"] = cache;
        },
        &images);
    EXPECT_TRUE(pixels.ok()) << pixels.message();
    return pixels.ok() ? *pixels : ImageF();
  };
  int frame = 1;
  for (double angle : {0.0, 0.0, yaw, 0.0}) {
    const ImageF a = render(cached, angle, true, frame);
    const ImageF b = render(fresh, angle, false, frame);
    ASSERT_FALSE(a.empty());
    EXPECT_LE(aq::test::max_abs_diff(a, b), 1e-6) << "frame " << frame << " yaw " << angle;
    ++frame;
  }
}

TEST(Pigment, ObjectAnchoringWithoutPositionIsAnError) {
  const ImageF input = aq::test::random_image(16, 16, 1);
  auto out = aq::test::run_node("pigment", {{"image", input}}, {{"anchoring", "object"}},
                                options_for(input, "float"));
  ASSERT_FALSE(out.ok());
  EXPECT_NE(out.message().find("position"), std::string::npos) << out.message();
}

TEST(Pigment, NonFiniteTextureGivesFiniteOutput) {
  const ImageF input = aq::test::random_image(32, 32, 3);
  ImageF turbulence = aq::test::random_image(32, 32, 4);
  turbulence.at(5, 5, 0) = std::numeric_limits<float>::quiet_NaN();
  turbulence.at(6, 9, 0) = std::numeric_limits<float>::infinity();
  auto out = aq::test::run_node("pigment", {{"image", input}, {"turbulence", turbulence}},
                                {{"turbulence_weight", 2.0}}, options_for(input, "float"));
  ASSERT_TRUE(out.ok()) << out.message();
  EXPECT_TRUE(aq::test::all_finite(*out));
}

TEST(Pigment, OnePixelImage) {
  const ImageF input = aq::test::constant_image(1, 1, 0.2f, 0.4f, 0.6f, 1.0f);
  auto out =
      aq::test::run_node("pigment", {{"image", input}}, test_params(), options_for(input, "float"));
  ASSERT_TRUE(out.ok()) << out.message();
  const ImageF expected =
      aq::reference::pigment(input, {nullptr, nullptr, nullptr}, nullptr, reference_params());
  EXPECT_LE(aq::test::max_abs_diff(*out, expected), 1e-5);
}

}  // namespace
