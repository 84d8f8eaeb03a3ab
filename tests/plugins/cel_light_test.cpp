// Headless tests of the `cel_light` node fed with synthetic gbuffer images, against the CPU
// double-precision reference (reference/cel_shading.h, HSV done the textbook way):
// float and half precision, a sweep over levels, the hard cases (grey, black, values above 1,
// exactly on a level boundary, levels = 1, NaN input), the background, the shadow input and
// the caustic projection (neutral texture, strength, tiling, projection along the light).
#include <gtest/gtest.h>

#include <cmath>
#include <set>
#include <string>

#include "aquarelle/reference/cel_shading.h"
#include "aquarelle/reference/morphology.h"
#include "support/harness.h"

namespace {

using aq::ImageF;
using aq::reference::CelLightParams;

constexpr int kW = 64, kH = 48;

struct LightSetup {
  std::array<double, 3> light_direction{0.3, -1.0, -0.35};  // normalised by the scene node
  std::array<double, 3> light_color{1.0, 0.97, 0.9};
  double intensity = 1.3;
  std::array<double, 3> ambient{0.22, 0.27, 0.32};
  int levels = 4;
  bool quantize = true;
  std::string space = "display";
  bool floor = true;
  std::string plain = "light";
  std::string alpha = "opaque";
  double caustic_tile = 4.0;  // cel_light's own; 0 takes the scene's
  double scene_caustic_tile = 4.0;
  double caustic_strength = 1.0;
  int pcf_radius = 0;
  double water_height = 6.0;
};

std::string graph(const LightSetup& s, bool shadow, bool caustics) {
  nlohmann::json inputs = {{"scene", "scene.scene"},
                           {"position", "position.image"},
                           {"normal", "normal.image"},
                           {"albedo", "albedo.image"},
                           {"id", "id.image"}};
  nlohmann::json nodes = {{"scene",
                           {{"type", "scene"},
                            {"params",
                             {{"preset", "cube"},
                              {"light_direction", s.light_direction},
                              {"light_color", s.light_color},
                              {"light_intensity", s.intensity},
                              {"ambient", s.ambient},
                              {"water_height", s.water_height},
                              {"caustic_tile", s.scene_caustic_tile}}}}},
                          {"light",
                           {{"type", "cel_light"},
                            {"params",
                             {{"levels", s.levels},
                              {"quantize", s.quantize},
                              {"space", s.space},
                              {"floor", s.floor},
                              {"plain", s.plain},
                              {"alpha", s.alpha},
                              {"caustic_tile", s.caustic_tile},
                              {"caustic_strength", s.caustic_strength},
                              {"pcf_radius", s.pcf_radius}}}}}};
  for (const char* name : {"position", "normal", "albedo", "id"}) {
    nodes[name] = {{"type", "image_input"}, {"params", {{"name", name}}}};
  }
  if (shadow) {
    nodes["shadow"] = {{"type", "image_input"}, {"params", {{"name", "shadow"}}}};
    inputs["shadow"] = "shadow.image";
  }
  if (caustics) {
    nodes["caustics"] = {{"type", "image_input"}, {"params", {{"name", "caustics"}}}};
    inputs["caustics"] = "caustics.image";
  }
  nodes["light"]["inputs"] = inputs;
  return nlohmann::json({{"aquarelle", 1}, {"nodes", nodes}, {"output", "light.image"}}).dump();
}

struct GBufferImages {
  ImageF position, normal, albedo, id;
};

// Random unit normals (a quarter facing away from the light), albedo in [0, 1.5], a band of
// background pixels, positions inside the cube scene's bounds.
GBufferImages random_gbuffer(unsigned seed) {
  GBufferImages g;
  g.position = aq::test::random_image(kW, kH, seed, -0.5f, 0.5f);
  g.normal = aq::test::random_image(kW, kH, seed + 1, -1.0f, 1.0f);
  g.albedo = aq::test::random_image(kW, kH, seed + 2, 0.0f, 1.5f);
  g.id = aq::test::constant_image(kW, kH, 1, 1, 1, 1);
  for (int y = 0; y < kH; ++y) {
    for (int x = 0; x < kW; ++x) {
      double n[3] = {g.normal.at(x, y, 0), g.normal.at(x, y, 1) + 0.4, g.normal.at(x, y, 2)};
      double len = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
      for (int k = 0; k < 3; ++k) g.normal.at(x, y, k) = static_cast<float>(n[k] / len);
      g.position.at(x, y, 3) = g.normal.at(x, y, 3) = g.albedo.at(x, y, 3) = 1.0f;
      if (y < 3) g.id.at(x, y, 0) = 0.0f;  // background rows
    }
  }
  return g;
}

std::map<std::string, ImageF> as_inputs(const GBufferImages& g) {
  return {{"position", g.position}, {"normal", g.normal}, {"albedo", g.albedo}, {"id", g.id}};
}

ImageF run(const LightSetup& s, std::map<std::string, ImageF> images,
           const char* precision = "float") {
  aq::test::RenderOptions options;
  options.width = kW;
  options.height = kH;
  options.precision = precision;
  bool shadow = images.count("shadow") != 0, caustics = images.count("caustics") != 0;
  auto out = aq::test::render_graph(graph(s, shadow, caustics), options, images);
  EXPECT_TRUE(out.ok()) << (out.ok() ? "" : out.message());
  return out.ok() ? *out : ImageF();
}

CelLightParams reference_params(const LightSetup& s) {
  CelLightParams p;
  double len = std::sqrt(s.light_direction[0] * s.light_direction[0] +
                         s.light_direction[1] * s.light_direction[1] +
                         s.light_direction[2] * s.light_direction[2]);
  for (int k = 0; k < 3; ++k) {
    p.light_direction[k] = s.light_direction[k] / len;
    p.light_color[k] = s.light_color[k] * s.intensity;
    p.ambient[k] = s.ambient[k];
  }
  p.levels = s.levels;
  p.quantize = s.quantize;
  p.display = s.space == "display";
  p.floor = s.floor;
  return p;
}

// Max error over pixels whose value is not within `margin` of a level boundary (there the
// float and double computations may legitimately pick neighbouring levels).
struct Error {
  double max_abs = 0;
  double psnr = 0;
  int skipped = 0;
};
Error compare(const ImageF& got, const GBufferImages& g, const LightSetup& s,
              double margin = 1e-4) {
  CelLightParams p = reference_params(s);
  ImageF expected = aq::reference::cel_light(g.normal, g.albedo, g.id, p);
  CelLightParams unquantised = p;
  unquantised.quantize = false;
  ImageF raw = aq::reference::cel_light(g.normal, g.albedo, g.id, unquantised);
  Error e;
  ImageF got_kept = got, expected_kept = expected;
  for (int y = 0; y < kH; ++y) {
    for (int x = 0; x < kW; ++x) {
      double v = std::max({raw.at(x, y, 0), raw.at(x, y, 1), raw.at(x, y, 2)});
      double shown = p.display ? aq::reference::srgb_encode(v) : v;
      double t = shown * (s.levels - 1);
      bool near_boundary = s.quantize && s.levels > 1 && std::abs(t - std::floor(t) - 0.5) < margin;
      if (near_boundary) {
        ++e.skipped;
        for (int c = 0; c < 4; ++c) got_kept.at(x, y, c) = expected_kept.at(x, y, c) = 0;
      }
    }
  }
  e.max_abs = aq::test::max_abs_diff(got_kept, expected_kept, 3);
  double peak = 0;
  for (float v : expected.pixels) peak = std::max(peak, static_cast<double>(v));
  e.psnr = aq::test::psnr(got_kept, expected_kept, peak, 3);
  return e;
}

TEST(CelLight, MatchesTheReferenceInFloat) {
  GBufferImages g = random_gbuffer(21);
  LightSetup s;
  ImageF got = run(s, as_inputs(g));
  ASSERT_FALSE(got.empty());
  Error e = compare(got, g, s);
  EXPECT_LE(e.max_abs, 2e-5);
  EXPECT_GE(e.psnr, 90.0);
  EXPECT_LT(e.skipped, kW * kH / 100);
  RecordProperty("max_abs_float", std::to_string(e.max_abs));
  RecordProperty("psnr_float", std::to_string(e.psnr));
}

TEST(CelLight, MatchesTheReferenceInHalf) {
  GBufferImages g = random_gbuffer(22);
  LightSetup s;
  ImageF got = run(s, as_inputs(g), "half");
  ASSERT_FALSE(got.empty());
  // In half precision the inputs are RGBA16F too: albedo and normal carry 2^-11 relative
  // error in, the output another 2^-11 out; values reach ~2.6, so about 2.5e-3 at most. Pixels
  // that near a level boundary may legitimately land on the other level are left out.
  Error e = compare(got, g, s, 3e-3);
  EXPECT_LE(e.max_abs, 2.5e-3);
  EXPECT_GE(e.psnr, 60.0);
  RecordProperty("max_abs_half", std::to_string(e.max_abs));
}

TEST(CelLight, LevelsSweepAndPlainDiffuse) {
  GBufferImages g = random_gbuffer(23);
  for (int levels : {1, 2, 3, 4, 5, 8, 16}) {
    LightSetup s;
    s.levels = levels;
    Error e = compare(run(s, as_inputs(g)), g, s);
    EXPECT_LE(e.max_abs, 2e-5) << levels << " levels";
  }
  // Every combination of space and floor follows the reference too.
  for (const char* space : {"display", "linear"}) {
    for (bool floor : {true, false}) {
      LightSetup s;
      s.space = space;
      s.floor = floor;
      Error e = compare(run(s, as_inputs(g)), g, s);
      EXPECT_LE(e.max_abs, 2e-5) << space << (floor ? " with" : " without") << " floor";
    }
  }
  LightSetup plain;
  plain.quantize = false;
  Error e = compare(run(plain, as_inputs(g)), g, plain);
  EXPECT_LE(e.max_abs, 2e-5);
  EXPECT_EQ(e.skipped, 0);
}

// A light straight down with white colour and no ambient on +y normals: lit = albedo exactly.
LightSetup overhead() {
  LightSetup s;
  s.light_direction = {0, -1, 0};
  s.light_color = {1, 1, 1};
  s.intensity = 1.0;
  s.ambient = {0, 0, 0};
  return s;
}

GBufferImages flat_gbuffer(float r, float g_, float b) {
  GBufferImages g;
  g.position = aq::test::constant_image(kW, kH, 0, 0, 0, 1);
  g.normal = aq::test::constant_image(kW, kH, 0, 1, 0, 1);
  g.albedo = aq::test::constant_image(kW, kH, r, g_, b, 1);
  g.id = aq::test::constant_image(kW, kH, 1, 1, 1, 1);
  return g;
}

TEST(CelLight, GreyStaysGreyAndBlackStaysBlack) {
  GBufferImages g = random_gbuffer(24);
  for (int y = 0; y < kH; ++y)
    for (int x = 0; x < kW; ++x) {
      float v = (x % 4 == 0) ? 0.0f : g.albedo.at(x, y, 0);
      for (int c = 0; c < 3; ++c) g.albedo.at(x, y, c) = v;
    }
  LightSetup s;
  s.light_color = {1, 1, 1};
  s.ambient = {0.25, 0.25, 0.25};
  ImageF got = run(s, as_inputs(g));
  ASSERT_FALSE(got.empty());
  for (int y = 3; y < kH; ++y)
    for (int x = 0; x < kW; ++x) {
      EXPECT_EQ(got.at(x, y, 0), got.at(x, y, 1)) << x << "," << y;
      EXPECT_EQ(got.at(x, y, 1), got.at(x, y, 2)) << x << "," << y;
      if (x % 4 == 0) {
        EXPECT_EQ(got.at(x, y, 0), 0.0f) << x << "," << y;
      }
    }
}

TEST(CelLight, ValuesAboveOneStayHdr) {
  // Linear space: v = 2.9: nearest level of 4 is 3 (= 9/3); hue and saturation kept.
  LightSetup s = overhead();
  s.space = "linear";
  ImageF got = run(s, as_inputs(flat_gbuffer(2.9f, 1.45f, 0.58f)));
  ASSERT_FALSE(got.empty());
  EXPECT_NEAR(got.at(10, 10, 0), 3.0, 1e-5);
  EXPECT_NEAR(got.at(10, 10, 1), 1.5, 1e-5);
  EXPECT_NEAR(got.at(10, 10, 2), 0.6, 1e-5);
  // Display space: the sRGB steps continue above 1 (srgb(2.9) = 1.589, nearest level 5/3).
  s.space = "display";
  ImageF display = run(s, as_inputs(flat_gbuffer(2.9f, 1.45f, 0.58f)));
  ASSERT_FALSE(display.empty());
  const double v = aq::reference::srgb_decode(5.0 / 3.0);
  EXPECT_NEAR(display.at(10, 10, 0), v, 1e-5 * v);
  EXPECT_NEAR(display.at(10, 10, 1), v / 2, 1e-5 * v);
  EXPECT_NEAR(display.at(10, 10, 2), v / 5, 1e-5 * v);
}

TEST(CelLight, ExactlyOnALevelBoundaryIsStableAndRoundsUp) {
  LightSetup s = overhead();
  s.space = "linear";  // boundaries exactly representable in linear values
  s.floor = false;
  s.levels = 2;  // boundary at v = 0.5, exactly representable: rounds half up to 1
  ImageF got = run(s, as_inputs(flat_gbuffer(0.5f, 0.25f, 0.0f)));
  ASSERT_FALSE(got.empty());
  EXPECT_EQ(got.at(5, 5, 0), 1.0f);
  EXPECT_EQ(got.at(5, 5, 1), 0.5f);
  EXPECT_EQ(got.at(5, 5, 2), 0.0f);
  const auto expected = aq::reference::cel_shade({0.5, 0.25, 0.0}, 2, false, false);
  EXPECT_NEAR(expected[0], 1.0, 1e-12);
  EXPECT_NEAR(expected[1], 0.5, 1e-12);

  // 4 levels: v = 1/6 sits on the boundary between 0 and 1/3 up to float rounding: either
  // level is right, but every pixel and every run picks the same one.
  s.levels = 4;
  ImageF a = run(s, as_inputs(flat_gbuffer(1.0f / 6.0f, 1.0f / 12.0f, 1.0f / 6.0f)));
  ImageF b = run(s, as_inputs(flat_gbuffer(1.0f / 6.0f, 1.0f / 12.0f, 1.0f / 6.0f)));
  ASSERT_FALSE(a.empty());
  EXPECT_EQ(a.pixels, b.pixels);
  float v = a.at(0, 0, 0);
  EXPECT_TRUE(std::abs(v) < 1e-7 || std::abs(v - 1.0f / 3.0f) < 1e-6) << v;
  for (int y = 0; y < kH; ++y)
    for (int x = 0; x < kW; ++x) ASSERT_EQ(a.at(x, y, 0), v);
}

TEST(CelLight, OneLevelIsFlatColour) {
  GBufferImages g = random_gbuffer(25);
  LightSetup s;
  s.levels = 1;
  ImageF got = run(s, as_inputs(g));
  ASSERT_FALSE(got.empty());
  for (int y = 3; y < kH; ++y)
    for (int x = 0; x < kW; ++x) {
      float v = std::max({got.at(x, y, 0), got.at(x, y, 1), got.at(x, y, 2)});
      ASSERT_TRUE(std::abs(v - 1.0f) < 1e-5 || v == 0.0f) << v;
    }
}

// Issue 37, hard case: a dark green albedo (0.02, 0.08, 0.02) at N.L = 0.5 under a white light
// and no ambient: lit = (0.01, 0.04, 0.01). Quantised in linear light, v = 0.04 rounded to 0
// (black); at the defaults (display space, floor) it keeps a green of the first level or more.
TEST(CelLight, ADarkGreenHalfLitIsNotBlack) {
  LightSetup s = overhead();
  GBufferImages g = flat_gbuffer(0.02f, 0.08f, 0.02f);
  const float c = static_cast<float>(std::sqrt(0.75));
  for (int y = 0; y < kH; ++y)
    for (int x = 0; x < kW; ++x) {
      g.normal.at(x, y, 0) = c;  // N.L = cos 60 degrees
      g.normal.at(x, y, 1) = 0.5f;
    }
  ImageF got = run(s, as_inputs(g));
  ASSERT_FALSE(got.empty());
  const auto expected = aq::reference::cel_shade({0.01, 0.04, 0.01}, 4);
  EXPECT_GT(expected[1], 0.04) << "the first display level is above the light's value";
  for (int y = 0; y < kH; ++y)
    for (int x = 0; x < kW; ++x) {
      ASSERT_GT(got.at(x, y, 1), 0.0f) << x << "," << y;
      ASSERT_NEAR(got.at(x, y, 1), expected[1], 1e-5) << x << "," << y;
      ASSERT_NEAR(got.at(x, y, 1), 4.0f * got.at(x, y, 0), 1e-5) << "hue kept";
    }
  // Without the floor, display space alone still keeps it (srgb(0.04) = 0.22 rounds to 1/3).
  s.floor = false;
  EXPECT_GT(run(s, as_inputs(g)).at(5, 5, 1), 0.0f);
  // Linear space without the floor is the old crush.
  s.space = "linear";
  EXPECT_EQ(run(s, as_inputs(g)).at(5, 5, 1), 0.0f);
}

// Issue 37, hard case: a textured checker of dark and light squares (a crate's checks), lit
// from every side by random normals (a quarter facing away), with a faint ambient: no pixel
// whose albedo is not black renders black, hue is kept, and the reference agrees.
TEST(CelLight, ACheckerOfDarkAndLightSquaresNeverGoesBlack) {
  GBufferImages g = random_gbuffer(31);
  const float dark[3] = {0.03f, 0.012f, 0.006f}, light[3] = {0.75f, 0.6f, 0.4f};
  for (int y = 0; y < kH; ++y)
    for (int x = 0; x < kW; ++x) {
      const bool is_dark = ((x / 8) + (y / 8)) % 2 == 0;
      for (int k = 0; k < 3; ++k) g.albedo.at(x, y, k) = is_dark ? dark[k] : light[k];
      g.id.at(x, y, 0) = 1.0f;
    }
  LightSetup s;
  s.ambient = {0.05, 0.06, 0.07};
  ImageF got = run(s, as_inputs(g));
  ASSERT_FALSE(got.empty());
  for (int y = 0; y < kH; ++y)
    for (int x = 0; x < kW; ++x) {
      const float v = std::max({got.at(x, y, 0), got.at(x, y, 1), got.at(x, y, 2)});
      ASSERT_GT(v, 0.0f) << "black at " << x << "," << y;
      ASSERT_GE(got.at(x, y, 0), got.at(x, y, 1)) << "hue kept at " << x << "," << y;
    }
  Error e = compare(got, g, s);
  EXPECT_LE(e.max_abs, 2e-5);
}

// The light's `plain` output for setup `s` on g-buffer `g`.
aq::Result<ImageF> plain_output(const LightSetup& s, const GBufferImages& g) {
  aq::test::RenderOptions options;
  options.width = kW;
  options.height = kH;
  options.output = "light.plain";
  return aq::test::render_graph(graph(s, false, false), options, as_inputs(g));
}

// `plain` = regions: the second output holds a flat colour per object id (0 on the background),
// the source `edge` darkens outlines from (issue 37): constant inside an object whatever its
// light, far apart between neighbouring ids.
TEST(CelLight, RegionsAreAFlatColourPerObject) {
  GBufferImages g = random_gbuffer(32);
  for (int y = 3; y < kH; ++y)
    for (int x = 0; x < kW; ++x) g.id.at(x, y, 0) = static_cast<float>(1 + x / 16);
  LightSetup s;
  s.plain = "regions";
  auto regions = plain_output(s, g);
  ASSERT_TRUE(regions.ok()) << regions.message();
  for (int y = 0; y < kH; ++y)
    for (int x = 0; x < kW; ++x)
      for (int c = 0; c < 3; ++c) {
        const float id = g.id.at(x, y, 0);
        const double expected =
            id * std::array<double, 3>{0.6180339887, 0.7548776662, 0.5698402910}[c];
        ASSERT_NEAR(regions->at(x, y, c), expected - std::floor(expected), 1e-5) << x << "," << y;
      }
  for (int id = 0; id < 4; ++id) {  // background and ids 1..4 side by side
    double largest = 0;
    for (int c = 0; c < 3; ++c)
      largest = std::max(largest, std::abs(static_cast<double>(regions->at(16 * id + 8, 10, c)) -
                                           regions->at(16 * (id + 1) + 8, 10, c)));
    if (id + 1 < 4) {
      EXPECT_GT(largest, 0.1) << "ids " << id + 1 << " and " << id + 2;
    }
  }
  // The light itself is unchanged by what `plain` holds.
  LightSetup light = s;
  light.plain = "light";
  EXPECT_EQ(aq::test::max_abs_diff(run(s, as_inputs(g)), run(light, as_inputs(g))), 0.0);
}

// `alpha` = regions: the image's alpha holds the label erode and dilate hash from the region
// colour (reference/morphology.cpp, region_label, on the bytes of the `plain` = regions
// colour), so a confined chain with `labels` = alpha needs no region image; the colour is the
// same as with an opaque alpha.
TEST(CelLight, RegionLabelsInAlphaAreTheMorphologysHashOfTheRegions) {
  GBufferImages g = random_gbuffer(33);
  for (int y = 3; y < kH; ++y)
    for (int x = 0; x < kW; ++x) g.id.at(x, y, 0) = static_cast<float>(1 + x / 8 + 8 * (y / 24));
  LightSetup s;
  s.plain = "regions";
  s.alpha = "regions";
  auto regions = plain_output(s, g);
  ASSERT_TRUE(regions.ok()) << regions.message();
  const ImageF labelled = run(s, as_inputs(g));
  std::set<int> labels;
  for (int y = 0; y < kH; ++y) {
    for (int x = 0; x < kW; ++x) {
      const int label = aq::reference::region_label(regions->at(x, y, 0), regions->at(x, y, 1),
                                                    regions->at(x, y, 2));
      ASSERT_EQ(std::lround(labelled.at(x, y, 3) * 255.0), label) << x << "," << y;
      labels.insert(label);
    }
  }
  EXPECT_GE(labels.size(), 10u);  // the background and most of the 16 ids apart
  LightSetup opaque = s;
  opaque.alpha = "opaque";
  const ImageF plain_alpha = run(opaque, as_inputs(g));
  EXPECT_EQ(aq::test::max_abs_diff(labelled, plain_alpha, 3), 0.0);
  for (int y = 0; y < kH; ++y)
    for (int x = 0; x < kW; ++x) ASSERT_EQ(plain_alpha.at(x, y, 3), 1.0f);
}

TEST(CelLight, BackgroundGetsTheBackgroundColour) {
  GBufferImages g = random_gbuffer(26);
  ImageF got = run(LightSetup{}, as_inputs(g));
  ASSERT_FALSE(got.empty());
  for (int x = 0; x < kW; ++x) {
    EXPECT_FLOAT_EQ(got.at(x, 0, 0), 0.1f);
    EXPECT_FLOAT_EQ(got.at(x, 0, 1), 0.3f);
    EXPECT_FLOAT_EQ(got.at(x, 0, 2), 0.4f);
  }
}

TEST(CelLight, NaNInputStaysInItsPixel) {
  GBufferImages g = random_gbuffer(27);
  g.albedo.at(20, 20, 1) = std::nanf("");
  g.normal.at(30, 30, 0) = std::numeric_limits<float>::infinity();
  g.position.at(40, 40, 2) = std::nanf("");
  ImageF clean = run(LightSetup{}, as_inputs(random_gbuffer(27)));
  ImageF got = run(LightSetup{}, as_inputs(g));
  ASSERT_FALSE(got.empty());
  EXPECT_TRUE(aq::test::all_finite(got));
  EXPECT_EQ(got.at(21, 20, 0), clean.at(21, 20, 0));
  EXPECT_EQ(got.at(31, 30, 1), clean.at(31, 30, 1));
}

TEST(CelLight, ShadowInputDarkensToAmbient) {
  GBufferImages g = random_gbuffer(28);
  auto images = as_inputs(g);
  LightSetup s;
  // A map of zeros: every point is behind an occluder; only ambient remains.
  images["shadow"] = aq::test::constant_image(32, 32, 0, 0, 0, 1);
  ImageF dark = run(s, images);
  LightSetup ambient_only = s;
  ambient_only.intensity = 0.0;
  Error e = compare(dark, g, ambient_only);
  EXPECT_LE(e.max_abs, 2e-5);
  // A map of ones: nothing occludes; the same as no shadow map.
  images["shadow"] = aq::test::constant_image(32, 32, 1, 1, 1, 1);
  ImageF lit = run(s, images);
  ImageF none = run(s, as_inputs(g));
  EXPECT_EQ(aq::test::max_abs_diff(lit, none), 0.0);
}

TEST(CelLight, NeutralCausticsChangeNothingAndStrengthScalesTheDirectLight) {
  GBufferImages g = random_gbuffer(29);
  LightSetup s;
  s.quantize = false;
  auto images = as_inputs(g);
  ImageF none = run(s, images);
  images["caustics"] = aq::test::constant_image(16, 16, 1, 1, 1, 1);
  EXPECT_LE(aq::test::max_abs_diff(run(s, images), none), 1e-6);
  images["caustics"] = aq::test::constant_image(16, 16, 2, 2, 2, 1);
  s.caustic_strength = 0.0;
  EXPECT_LE(aq::test::max_abs_diff(run(s, images), none), 1e-6);
  // Strength 0.5 on a caustic of 2: direct light times 1.5, ambient unchanged.
  s.caustic_strength = 0.5;
  ImageF got = run(s, images);
  LightSetup brighter = s;
  brighter.intensity *= 1.5;
  Error e = compare(got, g, brighter);
  EXPECT_LE(e.max_abs, 2e-5);
}

TEST(CelLight, CausticsTileInWorldUnitsAndFollowTheLight) {
  // A caustic texture with one bright quadrant; albedo white, normals up, no ambient.
  LightSetup s = overhead();
  s.light_direction = {0.4, -1.0, 0.2};
  s.quantize = false;
  s.caustic_tile = 2.0;
  ImageF caustic(8, 8, 4, 1.0f);
  for (int y = 0; y < 4; ++y)
    for (int x = 0; x < 4; ++x) caustic.at(x, y, 0) = caustic.at(x, y, 1) = caustic.at(x, y, 2) = 3;
  GBufferImages g = flat_gbuffer(1, 1, 1);
  // Column pairs: x and x + 32 hold points one tile apart in world x, or moved along the light.
  const double len = std::sqrt(0.16 + 1.0 + 0.04);
  const double dir[3] = {0.4 / len, -1.0 / len, 0.2 / len};
  for (int y = 0; y < kH; ++y)
    for (int x = 0; x < 32; ++x) {
      double p[3] = {x * 0.061, -0.3 + 0.01 * (y % 5), y * 0.043};
      for (int k = 0; k < 3; ++k) g.position.at(x, y, k) = static_cast<float>(p[k]);
      double shift[3] = {0, 0, 0};
      if (y % 2 == 0) {
        shift[0] = s.caustic_tile;  // one period further in x
      } else {
        for (int k = 0; k < 3; ++k) shift[k] = -0.8 * dir[k];  // up along the light ray
      }
      for (int k = 0; k < 3; ++k) g.position.at(x + 32, y, k) = static_cast<float>(p[k] + shift[k]);
    }
  auto images = as_inputs(g);
  images["caustics"] = caustic;
  ImageF got = run(s, images);
  ASSERT_FALSE(got.empty());
  double worst = 0, lo = 1e9, hi = -1e9;
  for (int y = 0; y < kH; ++y)
    for (int x = 0; x < 32; ++x) {
      worst =
          std::max(worst, static_cast<double>(std::abs(got.at(x, y, 0) - got.at(x + 32, y, 0))));
      lo = std::min(lo, static_cast<double>(got.at(x, y, 0)));
      hi = std::max(hi, static_cast<double>(got.at(x, y, 0)));
    }
  EXPECT_LT(worst, 2e-3);
  EXPECT_LT(lo, 1.5) << "some points get the dark part of the texture";
  EXPECT_GT(hi, 2.0) << "and some the bright quadrant";
}

// caustic_tile 0 projects the texture with the scene's period (the one the caustics node sizes
// its texture for): the same picture as giving that period to cel_light itself.
TEST(CelLight, ZeroCausticTileTakesTheScenes) {
  LightSetup own = overhead();
  own.light_direction = {0.4, -1.0, 0.2};
  own.quantize = false;
  own.caustic_tile = 2.0;
  own.scene_caustic_tile = 7.0;
  LightSetup from_scene = own;
  from_scene.caustic_tile = 0.0;
  from_scene.scene_caustic_tile = 2.0;
  LightSetup other = from_scene;
  other.scene_caustic_tile = 3.0;
  ImageF caustic = aq::test::random_image(8, 8, 5, 0.0f, 3.0f);
  GBufferImages g = flat_gbuffer(1, 1, 1);
  for (int y = 0; y < kH; ++y)
    for (int x = 0; x < kW; ++x) {
      g.position.at(x, y, 0) = static_cast<float>(x * 0.07);
      g.position.at(x, y, 2) = static_cast<float>(y * 0.05);
    }
  auto images = as_inputs(g);
  images["caustics"] = caustic;
  const ImageF a = run(own, images), b = run(from_scene, images), c = run(other, images);
  ASSERT_FALSE(a.empty() || b.empty() || c.empty());
  EXPECT_EQ(aq::test::max_abs_diff(a, b), 0.0);
  EXPECT_GT(aq::test::max_abs_diff(b, c), 0.1) << "the scene's period is really used";
}

}  // namespace

namespace {

TEST(CelLight, WholeChainAtAnySizeFromOnePixel) {
  const std::string chain = R"({
    "aquarelle": 1,
    "nodes": {
      "scene": { "type": "scene", "params": { "preset": "plane_box", "smoothing": 7,
                 "camera_position": [2.0, 2.0, 3.0], "camera_target": [0.0, 0.3, 0.0] } },
      "gbuf": { "type": "gbuffer", "inputs": { "scene": "scene.scene" } },
      "shadow": { "type": "shadowmap", "params": { "size": 64 }, "inputs": { "scene": "scene.scene" } },
      "light": { "type": "cel_light", "inputs": { "scene": "scene.scene",
                 "position": "gbuf.position", "normal": "gbuf.normal", "albedo": "gbuf.albedo",
                 "id": "gbuf.id", "shadow": "shadow.depth" } }
    },
    "output": "light.image"
  })";
  for (auto [w, h] : {std::pair{1, 1}, std::pair{2, 300}, std::pair{301, 3}}) {
    aq::test::RenderOptions options;
    options.width = w;
    options.height = h;
    auto out = aq::test::render_graph(chain, options);
    ASSERT_TRUE(out.ok()) << out.message();
    EXPECT_EQ(out->width, w);
    EXPECT_EQ(out->height, h);
    EXPECT_TRUE(aq::test::all_finite(*out)) << w << "x" << h;
  }
}

}  // namespace

namespace {

// One pass writes both outputs: `plain` is the light of the same pass without the caustics.
TEST(CelLight, PlainOutputIsTheLightWithoutCaustics) {
  GBufferImages g = random_gbuffer(31);
  LightSetup s;
  auto images = as_inputs(g);
  images["caustics"] = aq::test::random_image(16, 16, 5, 0.0f, 3.0f);
  aq::test::RenderOptions options;
  options.width = kW;
  options.height = kH;
  options.output = "light.plain";
  auto plain = aq::test::render_graph(graph(s, false, true), options, images);
  ASSERT_TRUE(plain.ok()) << plain.message();
  options.output = "light.image";
  auto lit = aq::test::render_graph(graph(s, false, true), options, images);
  ASSERT_TRUE(lit.ok()) << lit.message();
  LightSetup no_caustics = s;
  no_caustics.caustic_strength = 0.0;
  auto without = aq::test::render_graph(graph(no_caustics, false, true), options, images);
  ASSERT_TRUE(without.ok()) << without.message();
  EXPECT_LE(aq::test::max_abs_diff(*plain, *without), 1e-6);
  EXPECT_GT(aq::test::max_abs_diff(*plain, *lit), 0.05) << "the caustics do change `image`";
}

}  // namespace
