// The g-buffer's packed `surface` (nodes/shaders/gbuffer_surface.glsl) and cel_light reading
// it: the light from `surface` must be the light from the g-buffer's own normal, albedo and id
// targets with normal and albedo rounded to the nearest half (rounded here on the CPU by
// Imath's half, independently of the shaders' packHalf2x16), bit for bit; a light without a
// surface, or with something else on `surface`, says how to connect it.
#include <gtest/gtest.h>

#include <Imath/half.h>

#include <string>

#include "support/harness.h"

namespace {

using aq::ImageF;

constexpr int kW = 96, kH = 54;

nlohmann::json scene_node(bool environment) {
  if (environment) return {{"type", "scene_join"}, {"params", {{"environment", "gradient"}}}};
  return {{"type", "scene"}, {"params", {{"preset", "underwater"}, {"seed", 7}}}};
}

nlohmann::json light_node(bool environment, const nlohmann::json& inputs) {
  return {{"type", "cel_light"},
          {"params", {{"levels", 4}, {"environment", environment}}},
          {"inputs", inputs}};
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

TEST(GBufferSurface, TheLightFromTheSurfaceIsTheLightFromTheTargetsRoundedToHalf) {
  for (bool environment : {false, true}) {
    SCOPED_TRACE(environment ? "environment behind an empty scene" : "the underwater scene");
    const nlohmann::json gbuffer = {{"type", "gbuffer"}, {"inputs", {{"scene", "scene.scene"}}}};
    nlohmann::json packed = {{"scene", scene_node(environment)},
                             {"gbuf", gbuffer},
                             {"light", light_node(environment, {{"scene", "scene.scene"},
                                                                {"position", "gbuf.position"},
                                                                {"surface", "gbuf.surface"}})}};
    const ImageF from_surface = render(packed, "light.image");

    std::map<std::string, ImageF> targets;
    for (const char* port : {"position", "normal", "albedo", "id"})
      targets[port] = render(packed, std::string("gbuf.") + port);
    targets["normal"] = rounded_to_half(targets["normal"]);
    targets["albedo"] = rounded_to_half(targets["albedo"]);
    nlohmann::json separate = {{"scene", scene_node(environment)},
                               {"light", light_node(environment, {{"scene", "scene.scene"},
                                                                  {"position", "position.image"},
                                                                  {"normal", "normal.image"},
                                                                  {"albedo", "albedo.image"},
                                                                  {"id", "id.image"}})}};
    for (const char* port : {"position", "normal", "albedo", "id"})
      separate[port] = {{"type", "image_input"}, {"params", {{"name", port}}}};
    const ImageF from_targets = render(separate, "light.image", targets);

    ASSERT_EQ(from_surface.pixels.size(), from_targets.pixels.size());
    EXPECT_EQ(aq::test::max_abs_diff(from_surface, from_targets), 0.0);
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

TEST(GBufferSurface, ALightWithoutASurfaceSaysWhatToConnect) {
  nlohmann::json nodes = {{"scene", scene_node(false)},
                          {"gbuf", {{"type", "gbuffer"}, {"inputs", {{"scene", "scene.scene"}}}}},
                          {"light", light_node(false, {{"scene", "scene.scene"},
                                                       {"position", "gbuf.position"},
                                                       {"normal", "gbuf.normal"}})}};
  nlohmann::json g = {{"aquarelle", 1}, {"nodes", nodes}, {"output", "light.image"}};
  auto missing = aq::test::render_graph(g.dump(), options("light.image"));
  ASSERT_FALSE(missing.ok());
  EXPECT_NE(missing.message().find("'light'"), std::string::npos) << missing.message();
  EXPECT_NE(missing.message().find("`surface`"), std::string::npos) << missing.message();

  g["nodes"]["light"]["inputs"] = {
      {"scene", "scene.scene"}, {"position", "gbuf.position"}, {"surface", "gbuf.normal"}};
  auto wrong = aq::test::render_graph(g.dump(), options("light.image"));
  ASSERT_FALSE(wrong.ok());
  EXPECT_NE(wrong.message().find("not a packed surface"), std::string::npos) << wrong.message();
}

}  // namespace
