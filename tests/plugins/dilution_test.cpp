// Headless tests of the `dilution` node against reference/dilution.h: random normals and
// albedo without and with object-space turbulence; full light dilutes to the paper colour, the
// shade darkens only as asked, the background passes unchanged; NaN stays put.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "aquarelle/reference/dilution.h"
#include "support/harness.h"

namespace {

using aq::ImageF;
using aq::reference::DilutionParams;

aq::Result<ImageF> run(const ImageF& albedo, const ImageF& normal, const ImageF* object,
                       const DilutionParams& p, const std::string& port = "image") {
  nlohmann::json nodes;
  std::map<std::string, ImageF> images{{"albedo", albedo}, {"normal", normal}};
  for (const char* name : {"albedo", "normal"}) {
    nodes[name] = {{"type", "image_input"}, {"params", {{"name", name}}}};
  }
  nlohmann::json inputs = {
      {"albedo", "albedo.image"}, {"normal", "normal.image"}, {"scene", "join.scene"}};
  if (object) {
    nodes["object"] = {{"type", "image_input"}, {"params", {{"name", "object"}}}};
    inputs["object"] = "object.image";
    images["object"] = *object;
  }
  nodes["join"] = {
      {"type", "scene_join"},
      {"params", {{"light_direction", {-p.to_light[0], -p.to_light[1], -p.to_light[2]}}}}};
  nodes["dil"] = {{"type", "dilution"},
                  {"inputs", inputs},
                  {"params",
                   {{"dilution", p.dilution},
                    {"diffuse_area", p.diffuse_area},
                    {"shade", p.shade},
                    {"turbulence", p.turbulence},
                    {"scale", p.scale},
                    {"octaves", p.octaves},
                    {"paper_color", {p.paper[0], p.paper[1], p.paper[2]}}}}};
  aq::test::RenderOptions options;
  options.width = albedo.width;
  options.height = albedo.height;
  return aq::test::render_graph(
      nlohmann::json({{"aquarelle", 1}, {"nodes", nodes}, {"output", "dil." + port}}).dump(),
      options, images);
}

ImageF random_normals(int w, int h, unsigned seed) {
  ImageF n = aq::test::random_image(w, h, seed, -1.0f, 1.0f);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      double l = 0;
      for (int c = 0; c < 3; ++c) l += double(n.at(x, y, c)) * n.at(x, y, c);
      for (int c = 0; c < 3; ++c) n.at(x, y, c) = static_cast<float>(n.at(x, y, c) / std::sqrt(l));
      n.at(x, y, 3) = 1.0f;
    }
  return n;
}

TEST(Dilution, MatchesReference) {
  ImageF albedo = aq::test::random_image(40, 32, 51);
  for (int x = 0; x < 40; ++x) albedo.at(x, 0, 3) = 0.0f;  // a background row
  const ImageF normal = random_normals(40, 32, 52);
  const ImageF object = aq::test::random_image(40, 32, 53, -2.0f, 2.0f);
  DilutionParams p;
  const double s = 1.0 / std::sqrt(3.0);
  p.to_light = {s, s, s};
  p.diffuse_area = 0.7;
  for (const ImageF* anchor : {static_cast<const ImageF*>(nullptr), &object}) {
    const auto expected = aq::reference::dilution(albedo, normal, anchor, p);
    auto got = run(albedo, normal, anchor, p);
    auto mask = run(albedo, normal, anchor, p, "dilution");
    ASSERT_TRUE(got.ok() && mask.ok()) << got.message() << mask.message();
    const double error = aq::test::max_abs_diff(*got, expected.image);
    // With turbulence the float FBM differs from the double one by ~1e-6 of its range.
    EXPECT_LE(error, anchor ? 1e-4 : 5e-6);
    EXPECT_LE(aq::test::max_abs_diff(*mask, expected.dilution, 3), anchor ? 1e-4 : 5e-6);
    std::printf("[dilution] %s float max abs %.3g\n", anchor ? "turbulent" : "smooth", error);
  }
}

TEST(Dilution, LightDilutesShadeDarkensOnlyAsAsked) {
  const ImageF albedo = aq::test::constant_image(4, 4, 0.2f, 0.4f, 0.6f);
  const ImageF up = aq::test::constant_image(4, 4, 0.0f, 1.0f, 0.0f);
  const ImageF down = aq::test::constant_image(4, 4, 0.0f, -1.0f, 0.0f);
  DilutionParams p;
  p.dilution = 1.0;
  p.turbulence = 0.0;
  auto lit = run(albedo, up, nullptr, p);
  ASSERT_TRUE(lit.ok()) << lit.message();
  EXPECT_NEAR(lit->at(1, 1, 0), 0.96f, 1e-6);  // full light: the paper colour
  p.shade = 0.0;
  auto unlit = run(albedo, down, nullptr, p);
  ASSERT_TRUE(unlit.ok()) << unlit.message();
  EXPECT_EQ(aq::test::max_abs_diff(*unlit, albedo, 3), 0.0);  // shade 0: the colour itself
}

TEST(Dilution, NaNStaysPut) {
  ImageF albedo = aq::test::random_image(16, 16, 54);
  ImageF normal = random_normals(16, 16, 55);
  normal.at(3, 3, 0) = std::numeric_limits<float>::quiet_NaN();
  albedo.at(7, 7, 1) = std::numeric_limits<float>::quiet_NaN();
  auto got = run(albedo, normal, nullptr, {});
  ASSERT_TRUE(got.ok()) << got.message();
  int non_finite = 0;
  for (int y = 0; y < 16; ++y)
    for (int x = 0; x < 16; ++x)
      for (int c = 0; c < 4; ++c) non_finite += std::isfinite(got->at(x, y, c)) ? 0 : 1;
  EXPECT_LE(non_finite, 1);
}

}  // namespace
