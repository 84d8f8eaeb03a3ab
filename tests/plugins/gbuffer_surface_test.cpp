// The g-buffer's packed `surface` (nodes/shaders/gbuffer_surface.glsl) and cel_light reading
// it: the light from `surface` alone (its depth rebuilt into the position on the camera's rays,
// its normal octahedral in 2 x 16 bits) must be the light from the g-buffer's own position,
// normal, albedo and id targets with the normal rounded through the octahedral square and the
// albedo to the nearest half (both rounded here on the CPU, independently of the shaders: the
// octahedral map in double, Imath's half), up to float rounding; the octahedral normal is closer
// to the float normal than a half-precision one; a light without a surface, or with something
// else on `surface`, says how to connect it.
#include <gtest/gtest.h>

#include <Imath/half.h>

#include <algorithm>
#include <cmath>
#include <string>

#include "support/harness.h"

namespace {

using aq::ImageF;

constexpr int kW = 96, kH = 54;

nlohmann::json scene_node(bool environment) {
  if (environment) return {{"type", "scene_join"}, {"params", {{"environment", "gradient"}}}};
  return {{"type", "scene"}, {"params", {{"preset", "underwater"}, {"seed", 7}}}};
}

// The light, cel shading off so that a difference of float rounding stays one (no level
// boundary turns it into a step); with the shadow map and the caustics (where the position
// matters) unless `normal_only`.
nlohmann::json light_node(bool environment, nlohmann::json inputs, bool normal_only = false) {
  inputs["scene"] = "scene.scene";
  if (!normal_only) {
    inputs["shadow"] = "shadow.depth";
    inputs["caustics"] = "caustics.image";
  }
  return {{"type", "cel_light"},
          {"params", {{"quantize", false}, {"environment", environment}}},
          {"inputs", inputs}};
}

nlohmann::json scene_nodes(bool environment) {
  return {{"scene", scene_node(environment)},
          {"shadow", {{"type", "shadowmap"}, {"inputs", {{"scene", "scene.scene"}}}}},
          {"caustics", {{"type", "caustics"}, {"inputs", {{"scene", "scene.scene"}}}}}};
}

aq::test::RenderOptions options(const std::string& output) {
  aq::test::RenderOptions o;
  o.width = kW;
  o.height = kH;
  o.precision = "float";
  o.output = output;
  return o;
}

ImageF render(const nlohmann::json& nodes, const std::string& output,
              const std::map<std::string, ImageF>& images = {}) {
  nlohmann::json g = {{"aquarelle", 1}, {"nodes", nodes}, {"output", output}};
  auto image = aq::test::render_graph(g.dump(), options(output), images);
  EXPECT_TRUE(image.ok()) << (image.ok() ? "" : image.message());
  return image.ok() ? *image : ImageF();
}

ImageF rounded_to_half(ImageF image) {
  for (float& v : image.pixels) v = static_cast<float>(Imath::half(v));
  return image;
}

// A unit normal through the octahedral square (Meyer et al. 2010) with each coordinate rounded
// as packSnorm2x16 rounds it, and back; 0 stays 0 (the background).
ImageF rounded_octahedral(ImageF image) {
  auto sign = [](double v) { return v >= 0.0 ? 1.0 : -1.0; };
  auto snorm16 = [](double v) {
    return std::max(std::round(std::clamp(v, -1.0, 1.0) * 32767.0) / 32767.0, -1.0);
  };
  for (int y = 0; y < image.height; ++y) {
    for (int x = 0; x < image.width; ++x) {
      const double n[3] = {image.at(x, y, 0), image.at(x, y, 1), image.at(x, y, 2)};
      const double l1 = std::abs(n[0]) + std::abs(n[1]) + std::abs(n[2]);
      if (l1 == 0.0) continue;
      double u = n[0] / l1, v = n[1] / l1;
      if (n[2] < 0.0) {
        const double folded_u = (1.0 - std::abs(v)) * sign(u);
        v = (1.0 - std::abs(u)) * sign(v);
        u = folded_u;
      }
      u = snorm16(u);
      v = snorm16(v);
      double d[3] = {u, v, 1.0 - std::abs(u) - std::abs(v)};
      if (d[2] < 0.0) {
        d[0] = (1.0 - std::abs(v)) * sign(u);
        d[1] = (1.0 - std::abs(u)) * sign(v);
      }
      const double length = std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
      for (int c = 0; c < 3; ++c) image.at(x, y, c) = static_cast<float>(d[c] / length);
    }
  }
  return image;
}

// The light from image inputs standing for the g-buffer's targets.
ImageF light_from_targets(bool environment, const std::map<std::string, ImageF>& targets,
                          bool normal_only = false) {
  nlohmann::json nodes = scene_nodes(environment);
  nodes["light"] = light_node(environment,
                              {{"position", "position.image"},
                               {"normal", "normal.image"},
                               {"albedo", "albedo.image"},
                               {"id", "id.image"}},
                              normal_only);
  for (const char* port : {"position", "normal", "albedo", "id"})
    nodes[port] = {{"type", "image_input"}, {"params", {{"name", port}}}};
  return render(nodes, "light.image", targets);
}

// The fraction of pixels where two images differ by more than `tolerance` in any channel.
double fraction_apart(const ImageF& a, const ImageF& b, double tolerance) {
  int apart = 0;
  for (int y = 0; y < a.height; ++y) {
    for (int x = 0; x < a.width; ++x) {
      bool far = false;
      for (int c = 0; c < 3; ++c) far = far || std::abs(a.at(x, y, c) - b.at(x, y, c)) > tolerance;
      apart += far ? 1 : 0;
    }
  }
  return static_cast<double>(apart) / (a.width * a.height);
}

TEST(GBufferSurface, TheLightFromTheSurfaceIsTheLightFromTheTargetsRounded) {
  for (bool environment : {false, true}) {
    SCOPED_TRACE(environment ? "environment behind an empty scene" : "the underwater scene");
    nlohmann::json packed = scene_nodes(environment);
    packed["gbuf"] = {{"type", "gbuffer"}, {"inputs", {{"scene", "scene.scene"}}}};
    packed["light"] = light_node(environment, {{"surface", "gbuf.surface"}});
    const ImageF from_surface = render(packed, "light.image");

    std::map<std::string, ImageF> targets;
    for (const char* port : {"position", "normal", "albedo", "id"})
      targets[port] = render(packed, std::string("gbuf.") + port);
    targets["normal"] = rounded_octahedral(targets["normal"]);
    targets["albedo"] = rounded_to_half(targets["albedo"]);
    const ImageF from_targets = light_from_targets(environment, targets);

    ASSERT_EQ(from_surface.pixels.size(), from_targets.pixels.size());
    // Float rounding: the position rebuilt from the depth and the normal decoded on the GPU
    // differ from the targets' in the last bits. A shadow-map tap may flip at a shadow's edge,
    // so a few pixels may be further apart, never many.
    EXPECT_LT(aq::test::mean_abs_diff(from_surface, from_targets, 3), 1e-4);
    EXPECT_LT(fraction_apart(from_surface, from_targets, 1e-4), 0.005);
    // The comparison sees both kinds of pixel: lit surfaces and the background.
    int background = 0;
    for (int y = 0; y < kH; ++y)
      for (int x = 0; x < kW; ++x) background += targets["id"].at(x, y, 0) == 0.0f ? 1 : 0;
    if (environment) {
      EXPECT_EQ(background, kW * kH);
    } else {
      EXPECT_GT(background, 0);
      EXPECT_LT(background, kW * kH);
    }
  }
}

// The packed normal's error against the float normal, seen in the light (albedo rounded to half
// on both sides, no shadow or caustics, so only the normal differs): below a half-precision
// normal target's.
TEST(GBufferSurface, TheOctahedralNormalIsCloserToTheFloatNormalThanHalves) {
  nlohmann::json packed = scene_nodes(false);
  packed["gbuf"] = {{"type", "gbuffer"}, {"inputs", {{"scene", "scene.scene"}}}};
  packed["light"] = light_node(false, {{"surface", "gbuf.surface"}}, true);
  const ImageF from_surface = render(packed, "light.image");
  std::map<std::string, ImageF> targets;
  for (const char* port : {"position", "normal", "albedo", "id"})
    targets[port] = render(packed, std::string("gbuf.") + port);
  targets["albedo"] = rounded_to_half(targets["albedo"]);
  const ImageF exact = light_from_targets(false, targets, true);
  targets["normal"] = rounded_to_half(targets["normal"]);
  const ImageF halves = light_from_targets(false, targets, true);

  const double octahedral_error = aq::test::mean_abs_diff(from_surface, exact, 3);
  const double half_error = aq::test::mean_abs_diff(halves, exact, 3);
  EXPECT_GT(half_error, 0.0);
  EXPECT_LT(octahedral_error, half_error);
  EXPECT_LT(octahedral_error, 1e-6);
}

TEST(GBufferSurface, ALightWithoutASurfaceSaysWhatToConnect) {
  nlohmann::json nodes = scene_nodes(false);
  nodes["gbuf"] = {{"type", "gbuffer"}, {"inputs", {{"scene", "scene.scene"}}}};
  nodes["light"] = light_node(false, {{"position", "gbuf.position"}, {"normal", "gbuf.normal"}});
  nlohmann::json g = {{"aquarelle", 1}, {"nodes", nodes}, {"output", "light.image"}};
  auto missing = aq::test::render_graph(g.dump(), options("light.image"));
  ASSERT_FALSE(missing.ok());
  EXPECT_NE(missing.message().find("'light'"), std::string::npos) << missing.message();
  EXPECT_NE(missing.message().find("`surface`"), std::string::npos) << missing.message();

  g["nodes"]["light"]["inputs"]["surface"] = "gbuf.normal";
  auto wrong = aq::test::render_graph(g.dump(), options("light.image"));
  ASSERT_FALSE(wrong.ok());
  EXPECT_NE(wrong.message().find("not a packed surface"), std::string::npos) << wrong.message();
}

}  // namespace
