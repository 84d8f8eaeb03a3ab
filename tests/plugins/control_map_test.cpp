// Headless tests of the `control_map` node: each object's art direction lands on its pixels
// (exactly, without FBM), the background is 0, the grazing channel grows towards silhouettes,
// object-space FBM varies the amounts along an object and moves with it, and the object-space
// position output matches the g-buffer's coverage; images from 1x1 up; NaN normals (a flattened
// object's NaN normal matrix; NaN normals in a file, which the import replaces) stay off the
// control map. (A NaN vertex position never reaches a scene: the object node refuses the file.)
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>

#include "support/harness.h"

namespace {

using aq::ImageF;

std::string graph(double fbm_density, double x_position, const std::string& output) {
  nlohmann::json nodes;
  nodes["ball"] = {{"type", "object"},
                   {"params",
                    {{"source", "sphere"},
                     {"id", 3},
                     {"position", {x_position, 0.0, 0.0}},
                     {"bleed", 0.625},
                     {"edge_darkening", 1.5},
                     {"tremor", 0.25},
                     {"fbm_density", fbm_density},
                     {"fbm_scale", 3.0}}}};
  nodes["join"] = {
      {"type", "scene_join"},
      {"inputs", {{"objects", nlohmann::json::array({"ball.object"})}}},
      {"params", {{"camera_position", {0.0, 0.5, 3.0}}, {"camera_target", {0, 0.5, 0}}}}};
  nodes["cm"] = {{"type", "control_map"}, {"inputs", {{"scene", "join.scene"}}}};
  nodes["gbuf"] = {{"type", "gbuffer"}, {"inputs", {{"scene", "join.scene"}}}};
  return nlohmann::json({{"aquarelle", 1}, {"nodes", nodes}, {"output", output}}).dump();
}

aq::Result<ImageF> render(const std::string& json, int width = 64, int height = 64) {
  aq::test::RenderOptions options;
  options.width = width;
  options.height = height;
  return aq::test::render_graph(json, options);
}

// Every pixel of `control` is the object's amounts where the g-buffer's id is `id`, 0 elsewhere;
// returns how many pixels the object covers.
int expect_amounts_on_the_object(const ImageF& control, const ImageF& gbuffer_id, float id) {
  int covered = 0;
  for (int y = 0; y < control.height; ++y)
    for (int x = 0; x < control.width; ++x) {
      if (gbuffer_id.at(x, y, 0) == id) {
        ++covered;
        EXPECT_EQ(control.at(x, y, 0), 0.625f) << x << "," << y;
        EXPECT_EQ(control.at(x, y, 1), 1.5f) << x << "," << y;
        EXPECT_EQ(control.at(x, y, 3), 1.0f) << x << "," << y;  // unitless tremor mask
        EXPECT_TRUE(control.at(x, y, 2) >= 0.0f && control.at(x, y, 2) <= 1.0f) << x << "," << y;
      } else {
        for (int c = 0; c < 4; ++c) EXPECT_EQ(control.at(x, y, c), 0.0f) << x << "," << y;
      }
    }
  return covered;
}

TEST(ControlMap, ObjectAmountsOnItsPixelsZeroOnTheBackground) {
  auto control = render(graph(0.0, 0.0, "cm.control"));
  auto id = render(graph(0.0, 0.0, "gbuf.id"));
  ASSERT_TRUE(control.ok() && id.ok()) << control.message() << id.message();
  int covered = 0;
  for (int y = 0; y < 64; ++y)
    for (int x = 0; x < 64; ++x) {
      if (id->at(x, y, 0) == 3.0f) {
        ++covered;
        ASSERT_EQ(control->at(x, y, 0), 0.625f);
        ASSERT_EQ(control->at(x, y, 1), 1.5f);
        ASSERT_EQ(control->at(x, y, 3), 1.0f);  // unitless: the screen tremor's full amplitude
        ASSERT_GE(control->at(x, y, 2), 0.0f);
        ASSERT_LE(control->at(x, y, 2), 1.0f);
      } else {
        for (int c = 0; c < 4; ++c) ASSERT_EQ(control->at(x, y, c), 0.0f) << x << "," << y;
      }
    }
  EXPECT_GT(covered, 200);
  // Grazing: near 0 where the sphere faces the camera, large at its outline (along the row
  // through the middle of the sphere's pixels).
  int row_sum = 0, col_sum = 0;
  for (int y = 0; y < 64; ++y)
    for (int x = 0; x < 64; ++x)
      if (id->at(x, y, 0) == 3.0f) {
        row_sum += y;
        col_sum += x;
      }
  const int cy = row_sum / covered, cx = col_sum / covered;
  float centre = control->at(cx, cy, 2), rim = 0.0f;
  for (int x = 0; x < 64; ++x)
    if (id->at(x, cy, 0) == 3.0f) rim = std::max(rim, control->at(x, cy, 2));
  EXPECT_LT(centre, 0.1f);
  EXPECT_GT(rim, 0.5f);
}

TEST(ControlMap, FbmVariesAlongTheObjectAndSticksToIt) {
  auto still = render(graph(1.0, 0.0, "cm.control"));
  auto object = render(graph(1.0, 0.0, "cm.object"));
  auto moved = render(graph(1.0, 0.25, "cm.control"));
  auto moved_object = render(graph(1.0, 0.25, "cm.object"));
  ASSERT_TRUE(still.ok() && moved.ok() && object.ok() && moved_object.ok());
  float lo = 10.0f, hi = -10.0f;
  for (int y = 0; y < 64; ++y)
    for (int x = 0; x < 64; ++x)
      if (object->at(x, y, 3) == 1.0f) {
        lo = std::min(lo, still->at(x, y, 0));
        hi = std::max(hi, still->at(x, y, 0));
      }
  EXPECT_GT(hi - lo, 0.1f);  // varies
  // Where a pixel of the moved ball sees (nearly) the same object point as one of the still
  // ball, its amount is (nearly) the same: the variation is in object space.
  int compared = 0;
  double worst = 0.0;
  for (int y = 0; y < 64; ++y)
    for (int x = 0; x < 64; ++x) {
      if (moved_object->at(x, y, 3) != 1.0f) continue;
      for (int x0 = 0; x0 < 64; ++x0) {
        if (object->at(x0, y, 3) != 1.0f) continue;
        double d = 0.0;
        for (int c = 0; c < 3; ++c) d += std::abs(object->at(x0, y, c) - moved_object->at(x, y, c));
        if (d < 6e-3) {
          worst = std::max(worst, double(std::abs(still->at(x0, y, 0) - moved->at(x, y, 0))));
          ++compared;
        }
      }
    }
  EXPECT_GE(compared, 5);  // pixel centres seeing (nearly) the same object point
  EXPECT_LT(worst, 0.08);
}

TEST(ControlMap, FromOnePixelUp) {
  for (auto [w, h] : {std::pair{1, 1}, std::pair{1, 9}, std::pair{9, 1}, std::pair{5, 3}}) {
    auto control = render(graph(0.0, 0.0, "cm.control"), w, h);
    auto object = render(graph(0.0, 0.0, "cm.object"), w, h);
    auto id = render(graph(0.0, 0.0, "gbuf.id"), w, h);
    ASSERT_TRUE(control.ok() && object.ok() && id.ok()) << control.message() << object.message();
    ASSERT_EQ(control->width, w);
    ASSERT_EQ(control->height, h);
    EXPECT_TRUE(aq::test::all_finite(*control) && aq::test::all_finite(*object));
    expect_amounts_on_the_object(*control, *id, 3.0f);
  }
}

// One OBJ object: a quad on the left with sound normals, a quad on the right whose normals are
// NaN.
std::string broken_mesh_graph(const std::string& obj_path, const nlohmann::json& scale,
                              const std::string& output) {
  nlohmann::json nodes;
  nodes["mesh"] = {{"type", "object"},
                   {"params",
                    {{"source", "file"},
                     {"path", obj_path},
                     {"id", 3},
                     {"scale", scale},
                     {"bleed", 0.625},
                     {"edge_darkening", 1.5},
                     {"tremor", 0.25}}}};
  nodes["join"] = {
      {"type", "scene_join"},
      {"inputs", {{"objects", nlohmann::json::array({"mesh.object"})}}},
      {"params", {{"camera_position", {0.0, 0.5, 3.0}}, {"camera_target", {0, 0.5, 0}}}}};
  nodes["cm"] = {{"type", "control_map"}, {"inputs", {{"scene", "join.scene"}}}};
  nodes["gbuf"] = {{"type", "gbuffer"}, {"inputs", {{"scene", "join.scene"}}}};
  return nlohmann::json({{"aquarelle", 1}, {"nodes", nodes}, {"output", output}}).dump();
}

TEST(ControlMap, NaNInTheMeshDoesNotSpread) {
  namespace fs = std::filesystem;
  const fs::path dir =
      fs::temp_directory_path() / ("aq_control_map_test_" + std::to_string(getpid()));
  fs::create_directories(dir);
  const fs::path obj = dir / "broken.obj";
  std::ofstream(obj) << "v -1 0 0\nv -0.1 0 0\nv -0.1 1 0\nv -1 1 0\n"
                        "v 0.1 0 0\nv 1 0 0\nv 1 1 0\nv 0.1 1 0\n"
                        "vn 0 0 1\nvn nan nan nan\n"
                        "f 1//1 2//1 3//1\nf 1//1 3//1 4//1\n"
                        "f 5//2 6//2 7//2\nf 5//2 7//2 8//2\n";
  // Scale 0 along z flattens the quads in their own plane: the normal matrix (the inverse
  // transpose) is then NaN/Inf for every vertex.
  for (const nlohmann::json& scale : {nlohmann::json{1, 1, 1}, nlohmann::json{1, 1, 0}}) {
    auto control = render(broken_mesh_graph(obj.string(), scale, "cm.control"));
    auto object = render(broken_mesh_graph(obj.string(), scale, "cm.object"));
    auto id = render(broken_mesh_graph(obj.string(), scale, "gbuf.id"));
    ASSERT_TRUE(control.ok() && object.ok() && id.ok())
        << control.message() << object.message() << id.message();
    EXPECT_TRUE(aq::test::all_finite(*control)) << scale;
    EXPECT_TRUE(aq::test::all_finite(*object)) << scale;
    // Both quads are drawn, with their exact amounts, and nothing lands off them.
    EXPECT_GT(expect_amounts_on_the_object(*control, *id, 3.0f), 400) << scale;
  }
  fs::remove_all(dir);
}

}  // namespace
