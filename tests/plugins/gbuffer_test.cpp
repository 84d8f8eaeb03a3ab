// Headless tests of the `gbuffer` node: the background is marked explicitly (id 0, w = 0,
// depth = far plane), rasterised positions lie on the real surface and agree with the linear
// depth and the camera, face normals of an unsmoothed cube are exact, ids of several objects,
// half precision keeps positions exact enough for shadow lookups, any output size works.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <set>
#include <string>

#include <aquarelle/core/evaluator.h>
#include <aquarelle/core/gl_context.h>

#include "support/harness.h"

namespace {

using aq::ImageF;

const double kEye[3] = {1.6, 1.2, 2.2};
const double kTarget[3] = {0.0, 0.0, 0.0};
constexpr double kFarPlane = 200.0;  // the scene node's camera far plane

std::string graph(const std::string& preset, int smoothing = 0) {
  nlohmann::json g = {{"aquarelle", 1},
                      {"nodes",
                       {{"scene",
                         {{"type", "scene"},
                          {"params",
                           {{"preset", preset},
                            {"smoothing", smoothing},
                            {"camera_position", {kEye[0], kEye[1], kEye[2]}},
                            {"camera_target", {kTarget[0], kTarget[1], kTarget[2]}},
                            {"fov", 45.0}}}}},
                        {"gbuf", {{"type", "gbuffer"}, {"inputs", {{"scene", "scene.scene"}}}}}}},
                      {"output", "gbuf.albedo"}};
  return g.dump();
}

ImageF render(const std::string& preset, const std::string& port, int width = 64, int height = 64,
              const char* precision = "float") {
  aq::test::RenderOptions options;
  options.width = width;
  options.height = height;
  options.precision = precision;
  options.output = "gbuf." + port;
  auto image = aq::test::render_graph(graph(preset), options);
  EXPECT_TRUE(image.ok()) << (image.ok() ? "" : image.message());
  return image.ok() ? *image : ImageF();
}

TEST(GBuffer, BackgroundIsMarkedByIdZeroNotByTheNormal) {
  ImageF id = render("cube", "id");
  ImageF position = render("cube", "position");
  ImageF normal = render("cube", "normal");
  ImageF albedo = render("cube", "albedo");
  ImageF depth = render("cube", "depth");
  ASSERT_FALSE(id.empty());
  int background = 0, covered = 0;
  for (int y = 0; y < id.height; ++y) {
    for (int x = 0; x < id.width; ++x) {
      float object = id.at(x, y, 0);
      if (object == 0.0f) {
        ++background;
        EXPECT_EQ(position.at(x, y, 3), 0.0f);
        EXPECT_EQ(normal.at(x, y, 3), 0.0f);
        EXPECT_EQ(albedo.at(x, y, 3), 0.0f);
        EXPECT_FLOAT_EQ(depth.at(x, y, 0), kFarPlane);
      } else {
        ++covered;
        EXPECT_EQ(object, 1.0f);
        EXPECT_EQ(position.at(x, y, 3), 1.0f);
        EXPECT_EQ(normal.at(x, y, 3), 1.0f);
        EXPECT_EQ(albedo.at(x, y, 3), 1.0f);
      }
    }
  }
  EXPECT_GT(background, 500);  // corners are open water
  EXPECT_GT(covered, 500);     // the cube fills the middle
  EXPECT_EQ(id.at(0, 0, 0), 0.0f);
  EXPECT_EQ(id.at(32, 32, 0), 1.0f);
}

TEST(GBuffer, PositionsLieOnTheCubeAndMatchTheLinearDepth) {
  ImageF position = render("cube", "position");
  ImageF depth = render("cube", "depth");
  ImageF normal = render("cube", "normal");
  ASSERT_FALSE(position.empty());
  double forward[3], len = 0;
  for (int k = 0; k < 3; ++k) forward[k] = kTarget[k] - kEye[k], len += forward[k] * forward[k];
  for (double& f : forward) f /= std::sqrt(len);
  double worst_surface = 0, worst_depth = 0, worst_normal = 0;
  for (int y = 0; y < position.height; ++y) {
    for (int x = 0; x < position.width; ++x) {
      if (position.at(x, y, 3) != 1.0f) continue;
      double p[3] = {position.at(x, y, 0), position.at(x, y, 1), position.at(x, y, 2)};
      // On the unit cube's surface: the largest coordinate magnitude is 0.5.
      double m = std::max({std::abs(p[0]), std::abs(p[1]), std::abs(p[2])});
      worst_surface = std::max(worst_surface, std::abs(m - 0.5));
      double view_depth = 0;
      for (int k = 0; k < 3; ++k) view_depth += (p[k] - kEye[k]) * forward[k];
      worst_depth = std::max(worst_depth, std::abs(view_depth - depth.at(x, y, 0)));
      // Unsmoothed: the normal is the axis of the face the point lies on, facing the camera.
      int axis = 0;
      for (int k = 1; k < 3; ++k)
        if (std::abs(p[k]) > std::abs(p[axis])) axis = k;
      if (std::abs(std::abs(p[axis]) - 0.5) < 1e-4 && m - 1e-3 > std::abs(p[(axis + 1) % 3]) &&
          m - 1e-3 > std::abs(p[(axis + 2) % 3])) {
        worst_normal =
            std::max(worst_normal, std::abs(normal.at(x, y, axis) - (p[axis] > 0 ? 1.0 : -1.0)));
      }
    }
  }
  EXPECT_LT(worst_surface, 1e-4);
  EXPECT_LT(worst_depth, 1e-4);
  EXPECT_LT(worst_normal, 1e-5);
}

TEST(GBuffer, SeveralObjectsGetTheirOwnIds) {
  ImageF id = render("plane_box", "id");
  ASSERT_FALSE(id.empty());
  std::set<float> seen;
  for (int y = 0; y < id.height; ++y)
    for (int x = 0; x < id.width; ++x) seen.insert(id.at(x, y, 0));
  EXPECT_EQ(seen, (std::set<float>{0.0f, 1.0f, 2.0f}));
}

TEST(GBuffer, HalfPrecisionKeepsPositionsExact) {
  ImageF position = render("cube", "position", 64, 64, "half");
  ImageF normal = render("cube", "normal", 64, 64, "half");
  ASSERT_FALSE(position.empty());
  double worst = 0, worst_len = 0;
  for (int y = 0; y < position.height; ++y) {
    for (int x = 0; x < position.width; ++x) {
      if (position.at(x, y, 3) != 1.0f) continue;
      double m = std::max({std::abs(position.at(x, y, 0)), std::abs(position.at(x, y, 1)),
                           std::abs(position.at(x, y, 2))});
      worst = std::max(worst, std::abs(m - 0.5));
      double n = std::hypot(normal.at(x, y, 0), normal.at(x, y, 1), normal.at(x, y, 2));
      worst_len = std::max(worst_len, std::abs(n - 1.0));
    }
  }
  EXPECT_LT(worst, 1e-4) << "position stays RGBA32F in half precision";
  EXPECT_LT(worst_len, 2e-3) << "normals in RGBA16F are unit within half precision";
}

TEST(GBuffer, AnySizeFromOnePixel) {
  for (auto [w, h] : {std::pair{1, 1}, std::pair{97, 13}, std::pair{7, 200}}) {
    ImageF id = render("cube", "id", w, h);
    ASSERT_EQ(id.width, w);
    ASSERT_EQ(id.height, h);
    ImageF normal = render("cube", "normal", w, h);
    EXPECT_TRUE(aq::test::all_finite(normal));
  }
}

// With an environment (scene_join's default gradient; here with no objects, so every pixel is
// background) one pass writes the whole background instead of five clears and a masked pass:
// it must hold exactly what the clears wrote.
TEST(GBuffer, TheEnvironmentPassWritesTheClearValuesBehindTheScene) {
  aq::test::RenderOptions options;
  options.width = 96;
  options.height = 54;
  nlohmann::json g = {
      {"aquarelle", 1},
      {"nodes",
       {{"scene", {{"type", "scene_join"}, {"params", {{"environment", "gradient"}}}}},
        {"gbuf", {{"type", "gbuffer"}, {"inputs", {{"scene", "scene.scene"}}}}}}},
      {"output", "gbuf.albedo"}};
  std::map<std::string, ImageF> out;
  for (const char* port : {"id", "position", "normal", "albedo", "depth"}) {
    options.output = std::string("gbuf.") + port;
    auto image = aq::test::render_graph(g.dump(), options);
    ASSERT_TRUE(image.ok()) << image.message();
    out[port] = *image;
  }
  int background = 0;
  float far_depth = -1.0f, nearest_far = 0.0f;
  for (int y = 0; y < 54; ++y) {
    for (int x = 0; x < 96; ++x) {
      if (out["id"].at(x, y, 0) != 0.0f) {
        nearest_far = std::max(nearest_far, out["depth"].at(x, y, 0));
        continue;
      }
      ++background;
      for (int c = 0; c < 4; ++c) {
        EXPECT_EQ(out["position"].at(x, y, c), 0.0f) << x << "," << y;
        EXPECT_EQ(out["normal"].at(x, y, c), 0.0f) << x << "," << y;
      }
      EXPECT_EQ(out["albedo"].at(x, y, 3), 0.0f);
      EXPECT_GT(out["albedo"].at(x, y, 0) + out["albedo"].at(x, y, 1) + out["albedo"].at(x, y, 2),
                0.0f)
          << "the environment's colour";
      if (far_depth < 0.0f) far_depth = out["depth"].at(x, y, 0);
      EXPECT_EQ(out["depth"].at(x, y, 0), far_depth) << "one far plane behind everything";
    }
  }
  EXPECT_EQ(background, 96 * 54);
  EXPECT_GT(far_depth, nearest_far) << "the far plane, behind the camera's near plane";
}

}  // namespace

namespace {

// One g-buffer target of the underwater scene, from the node instance `node_id` (a new id is a
// new instance with nothing cached), at `frame`, seen from `eye`.
ImageF underwater_target(const std::string& node_id, const std::string& port, int frame,
                         const std::array<double, 3>& eye, bool cache_static = true) {
  nlohmann::json g = {
      {"aquarelle", 1},
      {"nodes",
       {{"scene",
         {{"type", "scene"}, {"params", {{"preset", "underwater"}, {"camera_position", eye}}}}},
        {node_id,
         {{"type", "gbuffer"},
          {"params", {{"cache_static", cache_static}}},
          {"inputs", {{"scene", "scene.scene"}}}}}}},
      {"output", node_id + "." + port}};
  aq::test::RenderOptions options;
  options.width = 96;
  options.height = 54;
  options.precision = "half";
  options.frame = frame;
  auto image = aq::test::render_graph(g.dump(), options);
  EXPECT_TRUE(image.ok()) << image.message();
  return image.ok() ? *image : ImageF();
}

// Meshes that did not move since the last call come from a cached layer and only the fish and
// the swaying seaweed are drawn over a copy of it: every target must be the one drawn from
// scratch, also on the call after the camera moved (the layer's key) and in half precision
// (the layer copies the formats the host chose).
TEST(GBuffer, CachedStillMeshesGiveTheTargetsDrawnFromScratch) {
  const std::array<double, 3> eye{0.3, 2.2, 6.0}, moved{1.0, 2.6, 5.0};
  for (const char* port : {"position", "normal", "albedo", "depth", "id"}) {
    const std::string warm = std::string("warm_") + port;
    ImageF at_three, at_four_moved;
    for (int frame = 1; frame <= 3; ++frame) at_three = underwater_target(warm, port, frame, eye);
    at_four_moved = underwater_target(warm, port, 4, moved);
    const ImageF at_five_moved = underwater_target(warm, port, 5, moved);
    ASSERT_FALSE(at_three.empty());
    const ImageF scratch_three = underwater_target("off", port, 3, eye, false);
    const ImageF scratch_five = underwater_target("off", port, 5, moved, false);
    EXPECT_EQ(aq::test::max_abs_diff(at_three, scratch_three), 0.0) << port;
    EXPECT_EQ(
        aq::test::max_abs_diff(at_four_moved, underwater_target("off", port, 4, moved, false)), 0.0)
        << port << " after the camera moved";
    EXPECT_EQ(aq::test::max_abs_diff(at_five_moved, scratch_five), 0.0) << port;
    EXPECT_GT(aq::test::max_abs_diff(scratch_three, underwater_target("off", port, 4, eye, false)),
              0.0)
        << port << ": something moved between frames 3 and 4";
  }
}

// A node instance made after another was destroyed (evaluator.clear(): the same node id, very
// likely the same address) must not be handed its predecessor's textures as its own kept
// outputs (aq_host::output_kept): each instance's tag is new.
TEST(GBuffer, ANewInstanceStartsFromScratchAfterTheOldOneIsGone) {
  auto context = aq::create_headless_context(aq::GlBackend::kAuto);
  ASSERT_TRUE(context.ok()) << context.message();
  aq::Evaluator evaluator(**context, aq::test::registry());
  aq::Evaluator scratch(**context, aq::test::registry());
  auto render = [](aq::Evaluator& e, int frame, bool cache) {
    nlohmann::json g = {{"aquarelle", 1},
                        {"nodes",
                         {{"scene", {{"type", "scene"}, {"params", {{"preset", "underwater"}}}}},
                          {"gbuf",
                           {{"type", "gbuffer"},
                            {"params", {{"cache_static", cache}}},
                            {"inputs", {{"scene", "scene.scene"}}}}}}},
                        {"output", "gbuf.normal"}};
    auto pixels = aq::test::evaluate_text(e, g.dump(), frame, [](aq::Graph& graph) {
      graph.settings.width = 96;
      graph.settings.height = 54;
    });
    EXPECT_TRUE(pixels.ok()) << pixels.message();
    return pixels.ok() ? *pixels : ImageF();
  };
  for (int frame = 1; frame <= 4; ++frame) {
    if (frame == 3) evaluator.clear();  // the instance and its outputs are gone
    const ImageF a = render(evaluator, frame, true);
    const ImageF b = render(scratch, frame, false);
    ASSERT_FALSE(a.empty());
    EXPECT_EQ(aq::test::max_abs_diff(a, b), 0.0) << "frame " << frame;
  }
}

}  // namespace
