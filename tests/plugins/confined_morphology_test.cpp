// `erode` and `dilate` with their `regions` input connected (issue 37, goal 4: thin features
// keep their continuity through the morphology): each pixel's window keeps to its own region,
// so a blade two pixels wide, thinner than the 3 x 3 opening, is not opened away. Checked
// against the direct definition in reference/morphology.cpp (confined_morphology) node by node
// in both precisions, every footprint and order, and through the flagship's chain erode 3 ->
// dilate 5 -> erode 3 in 8-bit blocks with its passes handed across the nodes (dilate then takes
// its columns first) and without.
#include <gtest/gtest.h>

#include "aquarelle/reference/morphology.h"
#include "plugins/watercolor_test_images.h"
#include "support/harness.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdlib>
#include <functional>
#include <queue>
#include <random>
#include <string>
#include <tuple>
#include <vector>

namespace aq::test {
namespace {

using aq::reference::MorphologyAxes;
using aq::reference::MorphologyFootprint;
using aq::reference::MorphologyOp;
using aq::reference::MorphologyOrder;
using aq::reference::MorphologyParams;

// The flagship's chain with `regions` fed to each node from a second image input.
const char* kConfinedChain = R"({
  "aquarelle": 1,
  "nodes": {
    "input": {"type": "image_input", "params": {"name": "image"}},
    "regions": {"type": "image_input", "params": {"name": "regions"}},
    "open_erode": {"type": "erode", "params": {"size": 3},
                   "inputs": {"image": "input.image", "regions": "regions.image"}},
    "dilate": {"type": "dilate", "params": {"size": 5},
               "inputs": {"image": "open_erode.image", "regions": "regions.image"}},
    "close_erode": {"type": "erode", "params": {"size": 3},
                    "inputs": {"image": "dilate.image", "regions": "regions.image"}}
  },
  "output": "close_erode.image"
})";

// The same after a size-1 erode that hands the chain an encoded 8-bit image in blocks, as the
// flagship's light does (an `image_input` gives the working format, so the first erode runs
// the plain passes and hands nothing on).
const char* kConfinedChainEncoded = R"({
  "aquarelle": 1,
  "nodes": {
    "input": {"type": "image_input", "params": {"name": "image"}},
    "regions": {"type": "image_input", "params": {"name": "regions"}},
    "encode": {"type": "erode", "params": {"size": 1}, "inputs": {"image": "input.image"}},
    "open_erode": {"type": "erode", "params": {"size": 3},
                   "inputs": {"image": "encode.image", "regions": "regions.image"}},
    "dilate": {"type": "dilate", "params": {"size": 5},
               "inputs": {"image": "open_erode.image", "regions": "regions.image"}},
    "close_erode": {"type": "erode", "params": {"size": 3},
                    "inputs": {"image": "dilate.image", "regions": "regions.image"}}
  },
  "output": "close_erode.image"
})";

// The encoded chain whose first node takes the labels from the image's alpha, as the flagship's
// open_erode takes them from the light's (the later nodes still read `regions`).
std::string labelled_chain() {
  nlohmann::json graph = nlohmann::json::parse(kConfinedChainEncoded);
  graph["nodes"]["open_erode"]["params"]["labels"] = "alpha";
  graph["nodes"]["open_erode"]["inputs"].erase("regions");
  return graph.dump();
}

// The same chain without `regions`: today's opening and closing.
const char* kOpenChain = R"({
  "aquarelle": 1,
  "nodes": {
    "input": {"type": "image_input", "params": {"name": "image"}},
    "open_erode": {"type": "erode", "params": {"size": 3}, "inputs": {"image": "input.image"}},
    "dilate": {"type": "dilate", "params": {"size": 5}, "inputs": {"image": "open_erode.image"}},
    "close_erode": {"type": "erode", "params": {"size": 3}, "inputs": {"image": "dilate.image"}}
  },
  "output": "close_erode.image"
})";

// Flat region colours (as cel_light's `plain` = regions writes them) in blobs of a few pixels,
// so every window meets two or three regions. Colours on the 8-bit grid, distinct labels.
ImageF blob_regions(int width, int height, unsigned seed) {
  std::mt19937 random(seed);
  std::uniform_int_distribution<int> coordinate(0, std::max(width, height));
  std::vector<std::pair<int, int>> centres;
  for (int i = 0; i < 24; ++i) centres.emplace_back(coordinate(random), coordinate(random));
  // fract(id · golden ratios), as cel_light, rounded to bytes; ids whose label repeats an
  // earlier one's are skipped (a shared label merges two regions: nothing to test there).
  const double golden[3] = {0.618034, 0.754878, 0.569840};
  auto colour_of = [&](int id, int c) {
    return std::round((id * golden[c] - std::floor(id * golden[c])) * 255.0) / 255.0;
  };
  std::vector<int> ids;
  std::vector<int> labels;
  for (int id = 1; ids.size() < centres.size(); ++id) {
    const int label =
        aq::reference::region_label(colour_of(id, 0), colour_of(id, 1), colour_of(id, 2));
    if (std::find(labels.begin(), labels.end(), label) != labels.end()) continue;
    ids.push_back(id);
    labels.push_back(label);
  }
  ImageF regions(width, height, 4, 1.0f);
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) {
      int nearest = 0;
      double best = 1e30;
      for (size_t i = 0; i < centres.size(); ++i) {
        const double dx = x - centres[i].first, dy = y - centres[i].second;
        if (dx * dx + dy * dy < best) best = dx * dx + dy * dy, nearest = static_cast<int>(i);
      }
      for (int c = 0; c < 3; ++c)
        regions.at(x, y, c) = static_cast<float>(colour_of(ids[nearest], c));
    }
  }
  return regions;
}

// The labels of the blob colours must be distinct for the test to mean what it says (a shared
// label merges two regions, which the reference would reproduce too, but tests nothing).
bool labels_distinct(const ImageF& regions) {
  std::vector<std::pair<int, std::vector<float>>> seen;
  for (int y = 0; y < regions.height; ++y) {
    for (int x = 0; x < regions.width; ++x) {
      std::vector<float> colour = {regions.at(x, y, 0), regions.at(x, y, 1), regions.at(x, y, 2)};
      const int label = aq::reference::region_label(colour[0], colour[1], colour[2]);
      for (const auto& [other, other_colour] : seen)
        if (other == label && other_colour != colour) return false;
      seen.emplace_back(label, colour);
    }
  }
  return true;
}

using NodeCase = std::tuple<std::string, int, std::string, std::string, std::string>;
class ConfinedMorphology : public ::testing::TestWithParam<NodeCase> {};

// One node on its own: rows first. Inputs on a 1/1024 grid are exact in half precision and the
// windows only select values, so the node reproduces the definition exactly.
TEST_P(ConfinedMorphology, MatchesTheDirectDefinitionExactly) {
  const auto& [node, size, footprint, mode, precision] = GetParam();
  const ImageF input = watercolor::quantized(random_image(53, 37, 5));
  const ImageF regions = blob_regions(53, 37, 9);
  ASSERT_TRUE(labels_distinct(regions));
  RenderOptions options;
  options.width = input.width;
  options.height = input.height;
  options.precision = precision;
  auto out = run_node(node, {{"image", input}, {"regions", regions}},
                      {{"size", size}, {"footprint", footprint}, {"mode", mode}}, options);
  ASSERT_TRUE(out.ok()) << out.message();
  const MorphologyParams params{
      node == "erode" ? MorphologyOp::kErode : MorphologyOp::kDilate, size,
      footprint == "disc" ? MorphologyFootprint::kDisc : MorphologyFootprint::kSquare,
      mode == "luminance" ? MorphologyOrder::kLuminance : MorphologyOrder::kPerChannel};
  const ImageF expected = aq::reference::confined_morphology(input, regions, params);
  EXPECT_EQ(max_abs_diff(*out, expected), 0.0);
  // And it is not the unconfined filter: the regions changed something.
  EXPECT_GT(max_abs_diff(aq::reference::morphology(input, params), expected, 3), 0.0);
}

INSTANTIATE_TEST_SUITE_P(Sweep, ConfinedMorphology,
                         ::testing::Combine(::testing::Values("erode", "dilate"),
                                            ::testing::Values(3, 5, 9),
                                            ::testing::Values("square", "disc"),
                                            ::testing::Values("channel", "luminance"),
                                            ::testing::Values("float", "half")));

// `labels` = alpha: the same windows as `regions`, from labels the writer put in the image's
// alpha (cel_light's `alpha` = regions writes region_label / 255 there); no region image.
class LabelsFromAlpha : public ::testing::TestWithParam<NodeCase> {};

TEST_P(LabelsFromAlpha, MatchTheDefinitionWithTheRegionsTheyLabel) {
  const auto& [node, size, footprint, mode, precision] = GetParam();
  ImageF input = watercolor::quantized(random_image(53, 37, 5));
  const ImageF regions = blob_regions(53, 37, 9);
  ASSERT_TRUE(labels_distinct(regions));
  for (int y = 0; y < input.height; ++y)
    for (int x = 0; x < input.width; ++x)
      input.at(x, y, 3) =
          static_cast<float>(aq::reference::region_label(regions.at(x, y, 0), regions.at(x, y, 1),
                                                         regions.at(x, y, 2)) /
                             255.0);
  RenderOptions options;
  options.width = input.width;
  options.height = input.height;
  options.precision = precision;
  auto out = run_node(
      node, {{"image", input}},
      {{"size", size}, {"footprint", footprint}, {"mode", mode}, {"labels", "alpha"}}, options);
  ASSERT_TRUE(out.ok()) << out.message();
  const MorphologyParams params{
      node == "erode" ? MorphologyOp::kErode : MorphologyOp::kDilate, size,
      footprint == "disc" ? MorphologyFootprint::kDisc : MorphologyFootprint::kSquare,
      mode == "luminance" ? MorphologyOrder::kLuminance : MorphologyOrder::kPerChannel};
  EXPECT_EQ(max_abs_diff(*out, aq::reference::confined_morphology(input, regions, params), 3), 0.0);
}

INSTANTIATE_TEST_SUITE_P(Sweep, LabelsFromAlpha,
                         ::testing::Combine(::testing::Values("erode", "dilate"),
                                            ::testing::Values(3, 5),
                                            ::testing::Values("square", "disc"),
                                            ::testing::Values("channel", "luminance"),
                                            ::testing::Values("float", "half")));

double encode(double c) {
  return std::sqrt(c / (1.0 + c));
}
double decode(double e) {
  const double y = e * e;
  return y / std::max(1.0 - y, 1.0 / 256.0);
}

// HDR colours on the 8-bit codes of AQ_FORMAT_RGBA8_HDR, so the encoded chain selects exactly.
ImageF light_on_codes(int width, int height, unsigned seed) {
  ImageF image(width, height, 4, 1.0f);
  std::mt19937 random(seed);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  for (float& v : image.pixels)
    v = static_cast<float>(
        decode(std::round(encode(4.0 * unit(random) * unit(random)) * 255.0) / 255.0));
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) image.at(x, y, 3) = 1.0f;
  return image;
}

Result<ImageF> render_chain(const char* graph, const ImageF& image, const ImageF& regions,
                            bool hand_on) {
  if (!hand_on) setenv("AQUARELLE_DEFER_AXIS", "0", 1);
  RenderOptions options;
  options.width = image.width;
  options.height = image.height;
  options.precision = "half";
  auto out = render_graph(graph, options, {{"image", image}, {"regions", regions}});
  unsetenv("AQUARELLE_DEFER_AXIS");
  return out;
}

// The chain erode 3 -> dilate 5 -> erode 3 by the definition, each node taking the axis given
// first.
ImageF reference_chain(const ImageF& image, const ImageF& regions,
                       const std::array<MorphologyAxes, 3>& axes) {
  using aq::reference::confined_morphology;
  const ImageF opened = confined_morphology(image, regions, {MorphologyOp::kErode, 3}, axes[0]);
  const ImageF dilated = confined_morphology(opened, regions, {MorphologyOp::kDilate, 5}, axes[1]);
  return confined_morphology(dilated, regions, {MorphologyOp::kErode, 3}, axes[2]);
}

// Largest |a - b| over (half's rounding of b): 1 or less when a is b stored in half.
double worst_over_half(const ImageF& a, const ImageF& b) {
  double worst = 0.0;
  for (size_t i = 0; i < a.pixels.size(); ++i)
    worst = std::max(worst, std::abs(a.pixels[i] - b.pixels[i]) /
                                (1.0e-3 * std::max(1.0, std::abs(double(b.pixels[i])))));
  return worst;
}

// A node takes rows first, except one that runs a pass handed to it, which takes that pass's
// axis first. Encoded (the flagship): open_erode hands its columns to dilate (columns first),
// dilate its rows to close_erode (rows first). From the working format: open_erode runs the
// plain passes and hands nothing; dilate (rows first) hands its columns to close_erode (columns
// first). Whole (AQUARELLE_DEFER_AXIS=0): rows first everywhere.
TEST(ConfinedMorphologyChain, HandedOnAndWholeMatchTheDefinition) {
  constexpr auto kRows = MorphologyAxes::kRowsFirst, kColumns = MorphologyAxes::kColumnsFirst;
  struct Case {
    const char* graph;
    bool hand_on;
    std::array<MorphologyAxes, 3> axes;
    const char* name;
  };
  const Case cases[] = {{kConfinedChainEncoded, true, {kRows, kColumns, kRows}, "encoded"},
                        // nullptr: labelled_chain()
                        {nullptr, true, {kRows, kColumns, kRows}, "labelled"},
                        {kConfinedChain, true, {kRows, kRows, kColumns}, "working format"},
                        {kConfinedChainEncoded, false, {kRows, kRows, kRows}, "whole, encoded"},
                        {kConfinedChain, false, {kRows, kRows, kRows}, "whole"}};
  for (const auto& [width, height] : {std::pair{64, 48}, {37, 21}, {9, 5}}) {
    ImageF light = light_on_codes(width, height, 3);
    const ImageF regions = blob_regions(width, height, 4);
    ASSERT_TRUE(labels_distinct(regions));
    // The labels in alpha for the labelled chain (the others read `regions` and leave alpha).
    for (int y = 0; y < height; ++y)
      for (int x = 0; x < width; ++x)
        light.at(x, y, 3) =
            static_cast<float>(aq::reference::region_label(regions.at(x, y, 0), regions.at(x, y, 1),
                                                           regions.at(x, y, 2)) /
                               255.0);
    for (const Case& c : cases) {
      const std::string labelled = labelled_chain();
      auto out =
          render_chain(c.graph != nullptr ? c.graph : labelled.c_str(), light, regions, c.hand_on);
      ASSERT_TRUE(out.ok()) << out.message();
      EXPECT_LE(worst_over_half(*out, reference_chain(light, regions, c.axes)), 1.0)
          << c.name << ", " << width << "x" << height;
    }
    // The orders differ somewhere (else the test could not tell them apart).
    EXPECT_GT(max_abs_diff(reference_chain(light, regions, {kRows, kColumns, kRows}),
                           reference_chain(light, regions, {kRows, kRows, kRows})),
              0.0);
  }
}

// The hard case: a blade two pixels wide, straight (vertical) and diagonal, lit in cel bands
// (two greens alternating every 6 pixels along it) on a blue-grey ground, through the
// flagship's chain. Blade pixels of the output: those nearer a blade green than the ground.
// They must join the blade's two ends by a 4-connected path for the vertical blade and an
// 8-connected one for the diagonal (whose pixels touch by corners every other row).
struct Blade {
  ImageF light, regions;
  std::vector<std::pair<int, int>> ends;
};

Blade blade(int width, int height, bool diagonal) {
  Blade b{ImageF(width, height, 4, 1.0f), ImageF(width, height, 4, 1.0f), {}};
  const float ground[3] = {0.10f, 0.30f, 0.40f};
  const float greens[2][3] = {{0.05f, 0.55f, 0.10f}, {0.20f, 0.90f, 0.25f}};
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) {
      const int offset = diagonal ? x - y - (width - height) / 2 : x - width / 2;
      const bool inside = y >= 4 && y < height - 4 && (offset == 0 || offset == 1);
      // A one-pixel caustic speckle in each band: the detail the opening is there to remove.
      const float speckle[3] = {0.50f, 1.00f, 0.50f};
      const float* colour =
          inside ? (y % 6 == 3 && offset == 0 ? speckle : greens[(y / 6) % 2]) : ground;
      for (int c = 0; c < 3; ++c) {
        b.light.at(x, y, c) = colour[c];
        b.regions.at(x, y, c) = inside ? 0.6f : 0.0f;  // the blade's region, and the ground's
      }
      if (inside && (y == 4 || y == height - 5) && offset == 0) b.ends.emplace_back(x, y);
    }
  }
  return b;
}

bool ends_connected(const ImageF& out, const Blade& b, bool eight) {
  auto is_blade = [&](int x, int y) {
    // Nearer a green than the ground, by green minus blue.
    return out.at(x, y, 1) - out.at(x, y, 2) > 0.2f;
  };
  std::vector<char> seen(static_cast<size_t>(out.width) * out.height, 0);
  std::queue<std::pair<int, int>> queue;
  const auto [sx, sy] = b.ends.front();
  if (!is_blade(sx, sy)) return false;
  queue.emplace(sx, sy);
  seen[static_cast<size_t>(sy) * out.width + sx] = 1;
  while (!queue.empty()) {
    const auto [x, y] = queue.front();
    queue.pop();
    if (std::pair{x, y} == b.ends.back()) return true;
    for (int dy = -1; dy <= 1; ++dy) {
      for (int dx = -1; dx <= 1; ++dx) {
        if ((dx == 0 && dy == 0) || (!eight && dx != 0 && dy != 0)) continue;
        const int nx = x + dx, ny = y + dy;
        if (nx < 0 || ny < 0 || nx >= out.width || ny >= out.height) continue;
        char& s = seen[static_cast<size_t>(ny) * out.width + nx];
        if (s || !is_blade(nx, ny)) continue;
        s = 1;
        queue.emplace(nx, ny);
      }
    }
  }
  return false;
}

TEST(ConfinedMorphologyChain, ATwoPixelBladeKeepsAnUnbrokenPath) {
  for (bool diagonal : {false, true}) {
    const Blade b = blade(48, 40, diagonal);
    ASSERT_EQ(b.ends.size(), 2u);
    ASSERT_TRUE(ends_connected(b.light, b, diagonal)) << "the test's own blade";
    // Today's chain, unconfined: the 3 x 3 opening removes the blade (the issue's dots).
    auto open = render_chain(kOpenChain, b.light, b.regions, true);
    ASSERT_TRUE(open.ok()) << open.message();
    EXPECT_FALSE(ends_connected(*open, b, diagonal)) << (diagonal ? "diagonal" : "straight");
    for (const auto& [graph, hand_on] : {std::pair{kConfinedChainEncoded, true},
                                         {kConfinedChain, true},
                                         {kConfinedChain, false}}) {
      auto confined = render_chain(graph, b.light, b.regions, hand_on);
      ASSERT_TRUE(confined.ok()) << confined.message();
      EXPECT_TRUE(ends_connected(*confined, b, diagonal))
          << (diagonal ? "diagonal" : "straight") << (hand_on ? ", handed on" : ", whole");
      // Every blade pixel stays a blade green, and the ground takes no green from it.
      int wrong = 0;
      for (int y = 0; y < b.light.height; ++y)
        for (int x = 0; x < b.light.width; ++x)
          wrong += (b.regions.at(x, y, 0) > 0.0f) !=
                   (confined->at(x, y, 1) - confined->at(x, y, 2) > 0.2f);
      EXPECT_EQ(wrong, 0) << (diagonal ? "diagonal" : "straight");
      // The cel bands inside the blade are still abstracted: the chain is not the identity.
      EXPECT_GT(max_abs_diff(*confined, b.light, 3), 0.0);
    }
  }
}

// The flagship's own light (graphs/underwater.json at 256 x 144, frame 12): its chain, confined
// to the light's regions, against the definition applied to the light and regions read back.
// Half precision (the shipped render): the chain compares the light's 8-bit codes in blocks and
// hands its passes on (dilate takes columns first), the reference the values: the tolerance is
// the encoding's bound (hdr8.glsl) plus half's rounding. Float precision (the golden frames'):
// no codes, no blocks, rows first everywhere, exact up to float. A pixel that took another
// object's colour, or a window that left its object, is far outside either.
TEST(Flagship, TheChainKeepsToTheObjectsOfItsOwnLight) {
  constexpr auto kRows = MorphologyAxes::kRowsFirst, kColumns = MorphologyAxes::kColumnsFirst;
  for (const std::string precision : {"half", "float"}) {
    RenderOptions options;
    options.width = 256;
    options.height = 144;
    options.frame = 12;
    options.precision = precision;
    const std::string graph = std::string(AQ_SOURCE_DIR) + "/graphs/underwater.json";
    auto read = [&](const char* output) {
      RenderOptions o = options;
      o.output = output;
      return render_graph_file(graph, o);
    };
    auto light = read("light.image");
    auto regions = read("light.plain");
    auto chain = read("close_erode.image");
    ASSERT_TRUE(light.ok()) << light.message();
    ASSERT_TRUE(regions.ok()) << regions.message();
    ASSERT_TRUE(chain.ok()) << chain.message();
    const bool half = precision == "half";
    const ImageF expected =
        reference_chain(*light, *regions, {kRows, half ? kColumns : kRows, kRows});
    int outside = 0;
    for (int y = 0; y < expected.height; ++y) {
      for (int x = 0; x < expected.width; ++x) {
        for (int c = 0; c < 3; ++c) {
          const double want = expected.at(x, y, c), got = chain->at(x, y, c);
          const double e = encode(std::max(want, 0.0));
          const double allowed = half ? e * (1.0 + want) * (1.0 + want) / 255.0 +
                                            1.0e-3 * std::max(1.0, std::abs(want))
                                      : 1.0e-6 * std::max(1.0, std::abs(want));
          outside += std::abs(got - want) > allowed;
        }
      }
    }
    EXPECT_EQ(outside, 0) << precision;
    // The chain moved something.
    EXPECT_GT(max_abs_diff(*chain, *light, 3), 0.05) << precision;
  }
}

}  // namespace
}  // namespace aq::test
