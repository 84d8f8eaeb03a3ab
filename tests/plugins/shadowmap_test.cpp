// Headless tests of the `shadowmap` node, read through cel_light (unquantised, no ambient, so a
// plane pixel is either lit: albedo * N.L, or black). Compared against exact ray casting
// against the box of the `plane_box` preset (reference/shadow_reference.h): the shadow
// lies where expected, there is no acne on the plane at grazing (80 degree) light, the shadow
// does not detach from the box, a light parallel to the plane gives finite black, and the size
// parameter sets the map's resolution.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "aquarelle/reference/shadow_reference.h"
#include "support/harness.h"

namespace {

using aq::ImageF;

constexpr double kPlaneAlbedo = 0.7;  // plane_box's plane colour
constexpr int kSize = 128;

struct Light {
  double angle_from_vertical_degrees;
  double azimuth_degrees = 0.0;
  std::array<double, 3> direction() const {
    double a = angle_from_vertical_degrees * M_PI / 180.0;
    double b = azimuth_degrees * M_PI / 180.0;
    return {std::sin(a) * std::cos(b), -std::cos(a), std::sin(a) * std::sin(b)};
  }
};

std::string graph(const std::array<double, 3>& light, int map_size, int pcf_radius,
                  double slope_bias = 2.0, double constant_bias = 0.005, bool auto_size = false) {
  nlohmann::json g = {{"aquarelle", 1},
                      {"nodes",
                       {{"scene",
                         {{"type", "scene"},
                          {"params",
                           {{"preset", "plane_box"},
                            {"smoothing", 0},
                            {"camera_position", {0.0, 9.0, 5.0}},
                            {"camera_target", {0.0, 0.0, 0.0}},
                            {"fov", 60.0},
                            {"light_direction", {light[0], light[1], light[2]}},
                            {"light_color", {1.0, 1.0, 1.0}},
                            {"light_intensity", 1.0},
                            {"ambient", {0.0, 0.0, 0.0}}}}}},
                        {"gbuf", {{"type", "gbuffer"}, {"inputs", {{"scene", "scene.scene"}}}}},
                        {"shadow",
                         {{"type", "shadowmap"},
                          {"params",
                           {{"size", map_size},
                            {"slope_bias", slope_bias},
                            {"constant_bias", constant_bias},
                            {"auto_size", auto_size}}},
                          {"inputs", {{"scene", "scene.scene"}}}}},
                        {"light",
                         {{"type", "cel_light"},
                          {"params", {{"quantize", false}, {"pcf_radius", pcf_radius}}},
                          {"inputs",
                           {{"scene", "scene.scene"},
                            {"position", "gbuf.position"},
                            {"normal", "gbuf.normal"},
                            {"albedo", "gbuf.albedo"},
                            {"id", "gbuf.id"},
                            {"shadow", "shadow.depth"}}}}}}},
                      {"output", "light.image"}};
  return g.dump();
}

ImageF render(const std::string& g, const std::string& output, const char* precision = "float") {
  aq::test::RenderOptions options;
  options.width = kSize;
  options.height = kSize;
  options.precision = precision;
  options.output = output;
  auto image = aq::test::render_graph(g, options);
  EXPECT_TRUE(image.ok()) << (image.ok() ? "" : image.message());
  return image.ok() ? *image : ImageF();
}

struct Comparison {
  int plane_pixels = 0;
  int shadow_pixels = 0;   // in shadow according to the reference
  int wrong_interior = 0;  // disagreements away from the shadow's edge (acne, detachment)
  int wrong_edge = 0;      // disagreements within two pixels of the edge (resolution)
};

// Classifies every plane pixel (id 1) of the lit image as lit or shadowed and compares with
// ray casting from its gbuffer position.
Comparison compare_with_reference(const std::array<double, 3>& light, int map_size, int pcf,
                                  const char* precision = "float", double slope_bias = 2.0,
                                  double constant_bias = 0.005, bool auto_size = false) {
  const std::string g = graph(light, map_size, pcf, slope_bias, constant_bias, auto_size);
  ImageF lit = render(g, "light.image", precision);
  ImageF position = render(g, "gbuf.position", precision);
  ImageF id = render(g, "gbuf.id", precision);
  Comparison result;
  if (lit.empty() || position.empty() || id.empty()) return result;
  ImageF mask = aq::reference::box_shadow_mask(position, light, {-0.5, 0.0, -0.5}, {0.5, 1.0, 0.5});
  const double expected_lit = kPlaneAlbedo * -light[1];
  for (int y = 0; y < kSize; ++y) {
    for (int x = 0; x < kSize; ++x) {
      if (id.at(x, y, 0) != 1.0f) continue;
      ++result.plane_pixels;
      bool reference_lit = mask.at(x, y, 0) == 1.0f;
      result.shadow_pixels += reference_lit ? 0 : 1;
      bool gpu_lit = lit.at(x, y, 0) > 0.5 * expected_lit;
      if (gpu_lit == reference_lit) continue;
      bool near_edge = false;
      for (int dy = -2; dy <= 2; ++dy)
        for (int dx = -2; dx <= 2; ++dx) {
          int u = std::clamp(x + dx, 0, kSize - 1), v = std::clamp(y + dy, 0, kSize - 1);
          if (mask.at(u, v, 0) >= 0.0f && (mask.at(u, v, 0) == 1.0f) != reference_lit) {
            near_edge = true;
          }
        }
      (near_edge ? result.wrong_edge : result.wrong_interior) += 1;
    }
  }
  return result;
}

TEST(ShadowMap, ShadowLiesWhereRayCastingPutsIt) {
  for (Light light : {Light{45.0}, Light{30.0, 120.0}, Light{60.0, -70.0}}) {
    Comparison c = compare_with_reference(light.direction(), 1024, 0);
    EXPECT_GT(c.shadow_pixels, 40) << light.angle_from_vertical_degrees;
    EXPECT_EQ(c.wrong_interior, 0) << light.angle_from_vertical_degrees;
    EXPECT_LT(c.wrong_edge, c.plane_pixels / 100) << light.angle_from_vertical_degrees;
  }
}

// auto_size picks the map from the receivers in view (about a texel per pixel at the nearest);
// cel_light must find the matrix the map was drawn with from the map's size alone.
TEST(ShadowMap, AutoSizedMapIsSmallerAndShadowsStayWhereRayCastingPutsThem) {
  for (Light light : {Light{45.0}, Light{60.0, -70.0}}) {
    Comparison c = compare_with_reference(light.direction(), 4096, 1, "float", 2.0, 0.005, true);
    EXPECT_GT(c.shadow_pixels, 40) << light.angle_from_vertical_degrees;
    EXPECT_EQ(c.wrong_interior, 0) << light.angle_from_vertical_degrees;
    EXPECT_LT(c.wrong_edge, c.plane_pixels / 100) << light.angle_from_vertical_degrees;
  }
  aq::test::RenderOptions options;
  options.width = kSize;
  options.height = kSize;
  options.output = "shadow.depth";
  auto depth =
      aq::test::render_graph(graph(Light{45.0}.direction(), 4096, 1, 2.0, 0.005, true), options);
  ASSERT_TRUE(depth.ok()) << depth.message();
  EXPECT_EQ(depth->width, depth->height);
  EXPECT_EQ(depth->width % 16, 0);
  EXPECT_LT(depth->width, 4096) << "a " << kSize << " px view needs far fewer texels";
  EXPECT_GE(depth->width, kSize);
}

// Hard views for the fit to what the camera sees: inside the box (the nearest receiver is at
// the near plane: the cap), looking at the sky (nothing in view: the scene fit at the cap), and
// far away (a few texels are enough). The map stays a map of depths in every case.
TEST(ShadowMap, AutoSizeInHardViews) {
  struct View {
    std::array<double, 3> position, target;
    int expected_size;  // 0: less than the cap
  };
  for (const View& view :
       {View{{0.0, 0.5, 0.0}, {0.0, 0.5, -1.0}, 1024}, View{{0.0, 3.0, 0.0}, {0.0, 9.0, 0.1}, 1024},
        View{{0.0, 60.0, 90.0}, {0.0, 0.0, 0.0}, 0}}) {
    nlohmann::json g =
        nlohmann::json::parse(graph(Light{45.0}.direction(), 1024, 1, 2.0, 0.005, true));
    g["nodes"]["scene"]["params"]["camera_position"] = view.position;
    g["nodes"]["scene"]["params"]["camera_target"] = view.target;
    aq::test::RenderOptions options;
    options.width = 64;
    options.height = 48;
    options.output = "shadow.depth";
    auto depth = aq::test::render_graph(g.dump(), options);
    ASSERT_TRUE(depth.ok()) << depth.message();
    if (view.expected_size > 0) {
      EXPECT_EQ(depth->width, view.expected_size) << view.position[1];
    } else {
      EXPECT_LT(depth->width, 256) << "the scene is a few pixels on screen";
    }
    EXPECT_TRUE(aq::test::all_finite(*depth));
    float lo = 1e9f;
    for (int y = 0; y < depth->height; ++y)
      for (int x = 0; x < depth->width; ++x) lo = std::min(lo, depth->at(x, y, 0));
    EXPECT_LT(lo, 0.9f) << "the scene is in the map";
    options.output = "light.image";
    auto lit = aq::test::render_graph(g.dump(), options);
    ASSERT_TRUE(lit.ok()) << lit.message();
    EXPECT_TRUE(aq::test::all_finite(*lit));
  }
}

TEST(ShadowMap, NoAcneOnThePlaneAtGrazingLight) {
  // 80 degrees from the vertical: the plane's depth changes fast across each texel.
  for (int size : {256, 1024, 2048}) {
    for (int pcf : {0, 1}) {
      Comparison c = compare_with_reference(Light{80.0, 15.0}.direction(), size, pcf);
      EXPECT_GT(c.shadow_pixels, 100);
      EXPECT_EQ(c.wrong_interior, 0) << "size " << size << " pcf " << pcf;
      EXPECT_LT(c.wrong_edge, c.plane_pixels / 50) << "size " << size << " pcf " << pcf;
    }
  }
}

TEST(ShadowMap, WithoutBiasTheSameSetupShowsAcne) {
  // The comparison above can fail: with no bias the plane shadows itself at grazing light.
  Comparison c = compare_with_reference(Light{80.0, 15.0}.direction(), 1024, 0, "float", 0.0, 0.0);
  EXPECT_GT(c.wrong_interior, c.plane_pixels / 20);
}

TEST(ShadowMap, HalfPrecisionGivesTheSameShadows) {
  Comparison c = compare_with_reference(Light{70.0, 40.0}.direction(), 1024, 1, "half");
  EXPECT_EQ(c.wrong_interior, 0);
}

TEST(ShadowMap, LightParallelToThePlaneLeavesItBlackAndFinite) {
  ImageF lit = render(graph({1.0, 0.0, 0.0}, 512, 1), "light.image");
  ImageF id = render(graph({1.0, 0.0, 0.0}, 512, 1), "gbuf.id");
  ASSERT_FALSE(lit.empty());
  EXPECT_TRUE(aq::test::all_finite(lit));
  for (int y = 0; y < kSize; ++y) {
    for (int x = 0; x < kSize; ++x) {
      if (id.at(x, y, 0) == 1.0f) {
        ASSERT_EQ(lit.at(x, y, 0), 0.0f) << x << "," << y;
      }
    }
  }
}

TEST(ShadowMap, StraightDownLightIsStable) {
  // The light's view direction is parallel to the default up vector: the matrix must not
  // degenerate; the box's shadow hides under the box, so the whole visible plane is lit.
  Comparison c = compare_with_reference({0.0, -1.0, 0.0}, 1024, 1);
  EXPECT_EQ(c.wrong_interior, 0);
  EXPECT_GT(c.plane_pixels, 1000);
}

TEST(ShadowMap, SizeSetsTheResolutionAndValuesAreDepths) {
  for (int size : {16, 300, 1024}) {
    aq::test::RenderOptions options;
    options.width = 32;
    options.height = 32;
    options.output = "shadow.depth";
    auto depth = aq::test::render_graph(graph(Light{45.0}.direction(), size, 0), options);
    ASSERT_TRUE(depth.ok()) << depth.message();
    EXPECT_EQ(depth->width, size);
    EXPECT_EQ(depth->height, size);
    float lo = 1e9f, hi = -1e9f;
    for (int y = 0; y < size; ++y)
      for (int x = 0; x < size; ++x) {
        lo = std::min(lo, depth->at(x, y, 0));
        hi = std::max(hi, depth->at(x, y, 0));
      }
    EXPECT_GE(lo, 0.0f);
    EXPECT_LE(hi, 1.1f);  // 1 = nothing seen; geometry (plus its bias) inside the volume
    EXPECT_LT(lo, 0.9f);
  }
}

}  // namespace

namespace {

// The underwater scene's shadow map at `frame`, from a node instance named `node_id` (a new
// id is a new instance, with nothing cached).
ImageF underwater_shadow(const std::string& node_id, int frame) {
  nlohmann::json g = {{"aquarelle", 1},
                      {"nodes",
                       {{"scene", {{"type", "scene"}, {"params", {{"preset", "underwater"}}}}},
                        {node_id,
                         {{"type", "shadowmap"},
                          {"params", {{"size", 256}}},
                          {"inputs", {{"scene", "scene.scene"}}}}}}},
                      {"output", node_id + ".depth"}};
  aq::test::RenderOptions options;
  options.width = 64;
  options.height = 36;
  options.frame = frame;
  auto depth = aq::test::render_graph(g.dump(), options);
  EXPECT_TRUE(depth.ok()) << depth.message();
  return depth.ok() ? *depth : ImageF();
}

// Meshes that did not move since the last frame come from a cached map and only the moving
// ones (fish, swaying seaweed) are drawn again: the map must be the one drawn from scratch.
TEST(ShadowMap, CachedStillCastersGiveTheMapDrawnFromScratch) {
  ImageF first, later;
  for (int frame = 1; frame <= 4; ++frame) later = underwater_shadow("warm", frame);
  first = underwater_shadow("warm", 1);  // back to frame 1: the moving meshes move back
  const ImageF cold_later = underwater_shadow("cold_4", 4);
  const ImageF cold_first = underwater_shadow("cold_1", 1);
  ASSERT_FALSE(later.empty());
  EXPECT_EQ(aq::test::max_abs_diff(later, cold_later), 0.0);
  EXPECT_EQ(aq::test::max_abs_diff(first, cold_first), 0.0);
  EXPECT_GT(aq::test::max_abs_diff(cold_first, cold_later), 0.0) << "something moved";
}

}  // namespace
