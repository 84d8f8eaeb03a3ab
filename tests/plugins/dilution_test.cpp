// Headless tests of the `dilution` node against reference/dilution.h: random normals and
// albedo without and with object-space turbulence; full light dilutes to the paper colour, the
// cangiante lightens the lit side only, the shade darkens only as asked, the background passes
// unchanged; 1x1 up; NaN in any input stays on its pixel.
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
                    {"cangiante", p.cangiante},
                    {"turbulence", p.turbulence},
                    {"scale", p.scale},
                    {"octaves", p.octaves},
                    {"turbulence_bend", p.turbulence_bend},
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

TEST(Dilution, CangianteLightensTheLitSideOnly) {
  const ImageF albedo = aq::test::constant_image(4, 4, 0.2f, 0.4f, 0.6f);
  const ImageF up = aq::test::constant_image(4, 4, 0.0f, 1.0f, 0.0f);
  const ImageF down = aq::test::constant_image(4, 4, 0.0f, -1.0f, 0.0f);
  DilutionParams p;
  p.dilution = 0.0;
  p.turbulence = 0.0;
  p.shade = 0.0;
  p.cangiante = 0.3;
  auto lit = run(albedo, up, nullptr, p);
  auto unlit = run(albedo, down, nullptr, p);
  ASSERT_TRUE(lit.ok() && unlit.ok()) << lit.message() << unlit.message();
  // Full light: every channel 0.3 lighter (C + c · lit); unlit: the colour itself.
  EXPECT_NEAR(lit->at(2, 2, 0), 0.5f, 1e-6);
  EXPECT_NEAR(lit->at(2, 2, 1), 0.7f, 1e-6);
  EXPECT_NEAR(lit->at(2, 2, 2), 0.9f, 1e-6);
  EXPECT_EQ(aq::test::max_abs_diff(*unlit, albedo, 3), 0.0);
  // Half dilution in full light: halfway from the lighter colour to the paper.
  p.dilution = 0.5;
  auto both = run(albedo, up, nullptr, p);
  ASSERT_TRUE(both.ok()) << both.message();
  EXPECT_NEAR(both->at(1, 1, 0), 0.5f * (0.5f + 0.96f), 1e-6);
}

TEST(Dilution, FromOnePixelUp) {
  for (auto [w, h] : {std::pair{1, 1}, std::pair{1, 7}, std::pair{9, 1}, std::pair{3, 2}}) {
    const ImageF albedo = aq::test::random_image(w, h, 60 + w);
    const ImageF normal = random_normals(w, h, 61 + h);
    const ImageF object = aq::test::random_image(w, h, 62, -2.0f, 2.0f);
    DilutionParams p;
    const auto expected = aq::reference::dilution(albedo, normal, &object, p);
    auto got = run(albedo, normal, &object, p);
    ASSERT_TRUE(got.ok()) << w << "x" << h << ": " << got.message();
    ASSERT_EQ(got->width, w);
    ASSERT_EQ(got->height, h);
    EXPECT_LE(aq::test::max_abs_diff(*got, expected.image), 1e-4) << w << "x" << h;
  }
}

TEST(Dilution, NaNInTheObjectPositionsStaysOnItsPixel) {
  const ImageF albedo = aq::test::random_image(16, 16, 56);
  const ImageF normal = random_normals(16, 16, 57);
  const ImageF clean = aq::test::random_image(16, 16, 58, -2.0f, 2.0f);
  ImageF dirty = clean;
  dirty.at(5, 6, 0) = std::numeric_limits<float>::quiet_NaN();
  dirty.at(11, 2, 2) = std::numeric_limits<float>::infinity();
  auto a = run(albedo, normal, &clean, {});
  auto b = run(albedo, normal, &dirty, {});
  ASSERT_TRUE(a.ok() && b.ok()) << a.message() << b.message();
  EXPECT_TRUE(aq::test::all_finite(*b));  // a bad anchor means no turbulence there
  for (int y = 0; y < 16; ++y)
    for (int x = 0; x < 16; ++x) {
      if ((x == 5 && y == 6) || (x == 11 && y == 2)) continue;
      for (int c = 0; c < 4; ++c) ASSERT_EQ(a->at(x, y, c), b->at(x, y, c)) << x << "," << y;
    }
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

// Seed 002's cubism: the turbulence noise blended with a bent smoothstep (the seed's smoothstep
// called with the wrong edges). Against the CPU reference written from that definition, and far
// from the usual turbulence: the node had no such parameter before (the graph failed).
TEST(Dilution, CubismBendsTheTurbulenceSmoothstep) {
  const ImageF albedo = aq::test::constant_image(48, 40, 0.3f, 0.5f, 0.4f);
  const ImageF up = aq::test::constant_image(48, 40, 0.0f, 1.0f, 0.0f);
  const ImageF object = aq::test::random_image(48, 40, 61, -3.0f, 3.0f);
  DilutionParams p;
  p.dilution = 0.6;
  p.turbulence = 1.0;
  p.turbulence_bend = 0.8;
  const auto expected = aq::reference::dilution(albedo, up, &object, p);
  auto got = run(albedo, up, &object, p);
  ASSERT_TRUE(got.ok()) << got.message();
  // The bent blend's slope is 1.5 / (1 − bend) = 7.5: float rounding grows by as much.
  EXPECT_LE(aq::test::max_abs_diff(*got, expected.image), 1e-3);
  DilutionParams usual = p;
  usual.turbulence_bend = 0.0;
  const auto smooth = aq::reference::dilution(albedo, up, &object, usual);
  EXPECT_GT(aq::test::mean_abs_diff(expected.image, smooth.image), 0.01)
      << "the bent turbulence should differ clearly from the usual one";
}
