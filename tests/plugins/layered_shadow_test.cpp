// Soft shadows of the `layered` node (seed 003's last step, the blurred depth test): the box of
// the `plane_box` preset casts a shadow on the plane through scene -> gbuffer -> shadowmap ->
// layered. The CPU reference (reference/layered.h) is given the visibility and the gap behind
// the occluder from exact ray casting against the box (reference/shadow_reference.h), not from
// the shadow map, so the node's lookup is checked too.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <string>

#include "aquarelle/reference/layered.h"
#include "aquarelle/reference/shadow_reference.h"
#include "support/harness.h"

namespace {

using aq::ImageF;
using aq::reference::LayeredParams;

constexpr int kSize = 96;
const std::array<double, 3> kCamera{0.0, 4.0, 2.5};
const std::array<double, 3> kBoxLo{-0.5, 0.0, -0.5}, kBoxHi{0.5, 1.0, 0.5};

// 45 degrees from the vertical, turned 30 degrees towards the camera: no face the camera sees
// lies along the light (where lit and shadowed would be a matter of rounding).
std::array<double, 3> light_direction() {
  const double a = 45.0 * M_PI / 180.0, b = 30.0 * M_PI / 180.0;
  return {std::sin(a) * std::cos(b), -std::cos(a), std::sin(a) * std::sin(b)};
}

std::string graph(double shadows, double softness, const char* method = "exact") {
  const std::array<double, 3> l = light_direction();
  nlohmann::json g = {{"aquarelle", 1},
                      {"nodes",
                       {{"scene",
                         {{"type", "scene"},
                          {"params",
                           {{"preset", "plane_box"},
                            {"smoothing", 0},
                            {"camera_position", {kCamera[0], kCamera[1], kCamera[2]}},
                            {"camera_target", {0.0, 0.0, 0.0}},
                            {"fov", 60.0},
                            {"light_direction", {l[0], l[1], l[2]}}}}}},
                        {"gbuf", {{"type", "gbuffer"}, {"inputs", {{"scene", "scene.scene"}}}}},
                        {"shadow",
                         {{"type", "shadowmap"},
                          {"params", {{"size", 1024}, {"auto_size", false}}},
                          {"inputs", {{"scene", "scene.scene"}}}}},
                        {"layered",
                         {{"type", "layered"},
                          {"params",
                           {{"specular_threshold", 1.0},
                            {"method", method},  // exact: the definition
                            {"shadows", shadows},
                            {"shadow_softness", softness},
                            {"shadow_band", 0.05}}},
                          {"inputs",
                           {{"id", "gbuf.id"},
                            {"normal", "gbuf.normal"},
                            {"albedo", "gbuf.albedo"},
                            {"depth", "gbuf.depth"},
                            {"position", "gbuf.position"},
                            {"shadow", "shadow.depth"},
                            {"scene", "scene.scene"}}}}}}},
                      {"output", "layered.image"}};
  return g.dump();
}

ImageF render(const std::string& g, const std::string& output) {
  aq::test::RenderOptions options;
  options.width = kSize;
  options.height = kSize;
  options.output = output;
  auto image = aq::test::render_graph(g, options);
  EXPECT_TRUE(image.ok()) << (image.ok() ? "" : image.message());
  return image.ok() ? *image : ImageF();
}

// How far P lies behind the box along the light: the distance from P back to where the ray
// towards the light leaves the box (the surface the light sees first), slab method.
double gap_behind_box(const std::array<double, 3>& p, const std::array<double, 3>& to_light) {
  double t0 = -1e30, t1 = 1e30;
  for (int a = 0; a < 3; ++a) {
    if (std::abs(to_light[a]) < 1e-12) {
      if (p[a] < kBoxLo[a] || p[a] > kBoxHi[a]) return 0.0;
      continue;
    }
    double ta = (kBoxLo[a] - p[a]) / to_light[a], tb = (kBoxHi[a] - p[a]) / to_light[a];
    t0 = std::max(t0, std::min(ta, tb));
    t1 = std::min(t1, std::max(ta, tb));
  }
  return t1 >= std::max(t0, 0.0) ? t1 : 0.0;
}

// Visibility (1 lit, 0 shadowed) and gap per pixel by ray casting from the gbuffer positions
// on the plane (id 1); the convex box shadows only its own faces turned from the light (a ray
// cast from its surface would meet the box itself by rounding).
ImageF ray_cast_shadow(const ImageF& position, const ImageF& id, const ImageF& normal) {
  const std::array<double, 3> l = light_direction();
  const ImageF mask = aq::reference::box_shadow_mask(position, l, kBoxLo, kBoxHi);
  ImageF out(position.width, position.height, 4, 0.0f);
  for (int y = 0; y < position.height; ++y)
    for (int x = 0; x < position.width; ++x) {
      const double towards_light =
          -(normal.at(x, y, 0) * l[0] + normal.at(x, y, 1) * l[1] + normal.at(x, y, 2) * l[2]);
      const bool lit = id.at(x, y, 0) == 1.0f ? mask.at(x, y, 0) != 0.0f : towards_light > 0.0;
      out.at(x, y, 0) = lit ? 1.0f : 0.0f;
      if (!lit) {
        const std::array<double, 3> p{position.at(x, y, 0), position.at(x, y, 1),
                                      position.at(x, y, 2)};
        out.at(x, y, 1) = static_cast<float>(gap_behind_box(p, {-l[0], -l[1], -l[2]}));
      }
    }
  return out;
}

struct Frames {
  ImageF id, normal, albedo, depth, position;
};

Frames gbuffer() {
  const std::string g = graph(0.8, 4.0);
  return {render(g, "gbuf.id"), render(g, "gbuf.normal"), render(g, "gbuf.albedo"),
          render(g, "gbuf.depth"), render(g, "gbuf.position")};
}

LayeredParams params(double shadows, double softness) {
  LayeredParams p;
  p.specular_threshold = 1.0;
  p.light_direction = light_direction();
  p.view_direction = kCamera;  // towards the viewer from the target at the origin
  p.shadows = shadows;
  p.shadow_softness = softness;
  p.shadow_band = 0.05;
  return p;
}

double luminance(const ImageF& im, int x, int y) {
  return 0.2126 * im.at(x, y, 0) + 0.7152 * im.at(x, y, 1) + 0.0722 * im.at(x, y, 2);
}

TEST(LayeredShadow, SoftShadowMatchesTheReferenceFromRayCasting) {
  const Frames f = gbuffer();
  ASSERT_FALSE(f.position.empty());
  const ImageF visibility = ray_cast_shadow(f.position, f.id, f.normal);
  const ImageF gpu = render(graph(0.8, 4.0), "layered.image");
  ASSERT_FALSE(gpu.empty());
  const ImageF cpu = aq::reference::layered(f.id, f.normal, f.albedo, f.depth, nullptr,
                                            params(0.8, 4.0), &visibility);
  // The shadow map's texels move the binary edge by a pixel here and there; blurred, that
  // stays small (measured: 66 dB, max 0.012).
  EXPECT_GT(aq::test::psnr(gpu, cpu, 1.0, 3), 55.0);
  EXPECT_LT(aq::test::max_abs_diff(gpu, cpu, 3), 0.03);
}

// The fast method (the default) averages and blurs the shadow layer at the lists' resolution
// and divides after the bilinear enlargement: near the same reference (measured 36.2 dB, mean
// 3.8e-3, max 0.64 with the quarter resolution's other differences), the shadow still there.
TEST(LayeredShadow, FastMethodShadowStaysNearTheReference) {
  const Frames f = gbuffer();
  ASSERT_FALSE(f.position.empty());
  const ImageF visibility = ray_cast_shadow(f.position, f.id, f.normal);
  const ImageF fast = render(graph(0.8, 4.0, "fast"), "layered.image");
  const ImageF unshadowed = render(graph(0.0, 4.0, "fast"), "layered.image");
  ASSERT_FALSE(fast.empty());
  const ImageF cpu = aq::reference::layered(f.id, f.normal, f.albedo, f.depth, nullptr,
                                            params(0.8, 4.0), &visibility);
  const double psnr = aq::test::psnr(fast, cpu, 1.0, 3);
  std::printf("fast shadow against the reference: %.1f dB, mean %.2e, max %.3f\n", psnr,
              aq::test::mean_abs_diff(fast, cpu, 3), aq::test::max_abs_diff(fast, cpu, 3));
  EXPECT_GT(psnr, 33.0);
  EXPECT_GT(aq::test::max_abs_diff(fast, unshadowed, 3), 0.05) << "the shadow is painted";
}

TEST(LayeredShadow, ShadowIsATranslucentLayerWithASemiVisibleBand) {
  const Frames f = gbuffer();
  ASSERT_FALSE(f.position.empty());
  const ImageF visibility = ray_cast_shadow(f.position, f.id, f.normal);
  const ImageF with = render(graph(0.8, 4.0), "layered.image");
  const ImageF without = render(graph(0.0, 4.0), "layered.image");
  const ImageF hard = render(graph(0.8, 0.0), "layered.image");
  ASSERT_FALSE(with.empty() || without.empty() || hard.empty());
  // Plane pixels (id 1) deep inside the ray-cast shadow or well away from it.
  // (the blur reaches 4 sigma = 16 px into the lit plane)
  auto all_around = [&](int x, int y, float value, int r) {
    for (int dy = -r; dy <= r; ++dy)
      for (int dx = -r; dx <= r; ++dx) {
        const int u = std::clamp(x + dx, 0, kSize - 1), v = std::clamp(y + dy, 0, kSize - 1);
        if (f.id.at(u, v, 0) != 1.0f || visibility.at(u, v, 0) != value) return false;
      }
    return true;
  };
  int shadowed = 0, lit = 0, band = 0, hard_band = 0;
  double darkest = 0.0;
  for (int y = 0; y < kSize; ++y)
    for (int x = 0; x < kSize; ++x) {
      if (f.id.at(x, y, 0) != 1.0f) continue;
      const double drop = luminance(without, x, y) - luminance(with, x, y);
      const double hard_drop = luminance(without, x, y) - luminance(hard, x, y);
      darkest = std::max(darkest, drop);
      if (all_around(x, y, 0.0f, 2)) {
        ++shadowed;
        EXPECT_GT(drop, 0.05) << x << "," << y << ": the shadow glaze darkens";
      } else if (all_around(x, y, 1.0f, 17)) {
        ++lit;
        EXPECT_LT(std::abs(drop), 1e-4) << x << "," << y << ": lit plane unchanged";
      }
      // Semi-visible: between a fifth and four fifths of the full shadow.
      if (drop > 0.02 && drop < 0.08) ++band;
      if (hard_drop > 0.02 && hard_drop < 0.08) ++hard_band;
    }
  EXPECT_GT(shadowed, 20);
  EXPECT_GT(lit, 100);
  EXPECT_GT(darkest, 0.1);
  // The blurred layer passes from lit to shadowed over a band of pixels; the binary test
  // (softness 0) hardly has one.
  EXPECT_GT(band, 2 * hard_band + 20);
}

TEST(LayeredShadow, ShadowWithoutPositionOrSceneIsAClearError) {
  nlohmann::json g = nlohmann::json::parse(graph(0.8, 4.0));
  g["nodes"]["layered"]["inputs"].erase("position");
  aq::test::RenderOptions options;
  options.width = 32;
  options.height = 32;
  auto image = aq::test::render_graph(g.dump(), options);
  ASSERT_FALSE(image.ok());
  EXPECT_NE(image.message().find("position"), std::string::npos) << image.message();
  EXPECT_NE(image.message().find("connect"), std::string::npos) << image.message();
}

}  // namespace
