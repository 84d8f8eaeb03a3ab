// AQ_FORMAT_RGBA8_HDR (plugin.h, aquarelle/hdr8.glsl): linear HDR colour stored in 8 bits as
// e = sqrt(c / (1 + c)) between a writer and readers that all say AQ_PORT_HDR8, at half
// precision. The plan tests need no GL; the render tests compare the lever on and off
// (AQUARELLE_HDR8=0) against the encoding's stated bound, and check that erode and dilate,
// which never decode, are exact on the stored values.
#include <gtest/gtest.h>

#include <aquarelle/core/graph_io.h>
#include <aquarelle/core/plan.h>
#include <aquarelle/core/registry.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <map>
#include <random>
#include <string>

#include "support/harness.h"
#include "support/morphology_graphs.h"

namespace aq::test {
namespace {

double encode(double c) {
  return std::sqrt(c / (1.0 + c));
}
double decode(double e) {
  const double y = e * e;
  return y / std::max(1.0 - y, 1.0 / 256.0);
}
// hdr8.glsl: rounding e to 8 bits moves c by at most e (1 + c)^2 / 255.
double bound(double c) {
  return encode(c) * (1.0 + c) * (1.0 + c) / 255.0;
}
// Half precision rounds the working textures on either side: 2^-11 relative, twice.
double half_slack(double c) {
  return 1.0e-3 * std::max(1.0, std::abs(c));
}

// An encoded image passed through (erode of size 1) to a reader that cannot decode it.
const char* kPassThrough = R"({
  "aquarelle": 1,
  "nodes": {
    "input": {"type": "image_input", "params": {"name": "image"}},
    "erode": {"type": "erode", "params": {"size": 3}, "inputs": {"image": "input.image"}},
    "same": {"type": "erode", "params": {"size": 1}, "inputs": {"image": "erode.image"}},
    "half": {"type": "tint", "params": {"amount": 0.5, "tint": [0, 0, 0]},
             "inputs": {"image": "same.image"}}
  },
  "output": "half.image"
})";

const char* kWobble = R"({
  "aquarelle": 1,
  "nodes": {
    "input": {"type": "image_input", "params": {"name": "image"}},
    "erode": {"type": "erode", "params": {"size": 3}, "inputs": {"image": "input.image"}},
    "wobble": {"type": "wobble", "params": {"strength": 8.0}, "inputs": {"image": "erode.image"}}
  },
  "output": "wobble.image"
})";

// pigment writes encoded for blur, whose separable direct kernel (final quality, σmax above
// 1 px) reads the taps itself; the other kernels get the image decoded first.
std::string pigment_blur(const char* direct_kernel) {
  return std::string(R"({
  "aquarelle": 1,
  "nodes": {
    "input": {"type": "image_input", "params": {"name": "image"}},
    "pigment": {"type": "pigment", "params": {"turbulence_weight": 0.3, "grain_weight": 0.2},
                "inputs": {"image": "input.image"}},
    "blur": {"type": "blur", "params": {"sigma": 2.0, "depth_weight": 0.5, "radial_weight": 0.35,
                                        "direct_kernel": ")") +
         direct_kernel + R"("}, "inputs": {"image": "pigment.image"}}
  },
  "output": "blur.image"
})";
}

Plan plan_of(const ReadResult& read, const std::string& precision, bool hdr8 = true) {
  EXPECT_TRUE(read.ok());
  PlanOptions options;
  options.hdr8 = hdr8;
  Graph graph = read.graph;
  graph.settings.precision = precision;
  auto plan = compile_plan(graph, registry(), options);
  EXPECT_TRUE(plan.ok()) << plan.message();
  return plan.ok() ? *plan : Plan{};
}

uint32_t stored(const Plan& plan, const std::string& id, size_t output = 0) {
  const PlannedNode* node = plan.find(id);
  if (node == nullptr || output >= node->stored_formats.size()) return 0;
  return node->stored_formats[output];
}

TEST(Hdr8, TheFlagshipStoresItsLightMorphologyAndPigmentEncoded) {
  const ReadResult text = read_graph_file(source_path("graphs/underwater.json"), registry());
  const Plan plan = plan_of(text, "half");
  EXPECT_EQ(stored(plan, "light"), uint32_t{AQ_FORMAT_RGBA8_HDR});
  // Read by the next morphology node or the wobble, or (the wobble's chain, which ends at
  // pigment) by the blur: kept in 2 x 2 blocks.
  for (const char* id : {"open_erode", "dilate", "close_erode", "pigment"})
    EXPECT_EQ(stored(plan, id), uint32_t{AQ_FORMAT_RGBA8_HDR_BLOCKS}) << id;
  EXPECT_EQ(stored(plan, "light", 1), uint32_t{AQ_FORMAT_RGBA8}) << "plain: edge's source";
  for (const char* id : {"wobble", "edge", "blur", "gbuf"})
    EXPECT_NE(stored(plan, id), uint32_t{AQ_FORMAT_RGBA8_HDR}) << id;
  // Float precision asks for accuracy: nothing is encoded; nor with the lever off.
  for (const Plan& other : {plan_of(text, "float"), plan_of(text, "half", false)})
    for (const char* id : {"light", "open_erode", "dilate", "close_erode"}) {
      EXPECT_NE(stored(other, id), uint32_t{AQ_FORMAT_RGBA8_HDR}) << id;
      EXPECT_NE(stored(other, id), uint32_t{AQ_FORMAT_RGBA8_HDR_BLOCKS}) << id;
    }
}

TEST(Hdr8, AReaderThatCannotDecodeKeepsTheWorkingFormat) {
  const Plan plan = plan_of(read_graph_text(kPassThrough, registry(), "pass through"), "half");
  EXPECT_EQ(stored(plan, "erode"), uint32_t{AQ_FORMAT_RGBA8_HDR_BLOCKS}) << "read by an erode";
  EXPECT_EQ(stored(plan, "same"), 0u) << "read by a tint, which does not decode";
  EXPECT_EQ(stored(plan, "input"), 0u) << "image_input does not say it can write it";
}

// Light between 0 and 6 (the caustics' peaks), with alpha 1, in blocks and noise so that the
// morphology has edges to move.
ImageF hdr_image(int width, int height, bool on_codes) {
  ImageF image(width, height, 4, 1.0f);
  std::mt19937 random(7);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) {
      for (int c = 0; c < 3; ++c) {
        double value = 6.0 * std::pow(unit(random), 2.0);
        // A value whose code is exact: the encoding maps it to itself.
        if (on_codes) value = decode(std::round(encode(value) * 255.0) / 255.0);
        image.at(x, y, c) = static_cast<float>(value);
      }
    }
  }
  return image;
}

Result<ImageF> render(const char* graph, const ImageF& input, bool hdr8, bool fuse = true,
                      const char* quality = "final") {
  if (hdr8) {
    unsetenv("AQUARELLE_HDR8");
  } else {
    setenv("AQUARELLE_HDR8", "0", 1);
  }
  RenderOptions options;
  options.width = input.width;
  options.height = input.height;
  options.precision = "half";
  options.fuse_pointwise = fuse;
  options.quality = quality;
  auto image = render_graph(graph, options, {{"image", input}});
  unsetenv("AQUARELLE_HDR8");
  return image;
}

// render() with the lever `variable` switched off (=0) for this one render.
Result<ImageF> render_without(const char* variable, const char* graph, const ImageF& input) {
  setenv(variable, "0", 1);
  auto image = render(graph, input, true);
  unsetenv(variable);
  return image;
}

struct Comparison {
  double worst_over_bound = 0.0;  // max of |on - off| / (bound + slack)
  double mean_abs = 0.0;
  double max_abs = 0.0;
};

Comparison compare(const ImageF& on, const ImageF& off) {
  Comparison result;
  double sum = 0.0;
  size_t count = 0;
  for (int y = 0; y < on.height; ++y) {
    for (int x = 0; x < on.width; ++x) {
      for (int c = 0; c < 4; ++c) {
        const double a = on.at(x, y, c);
        const double b = off.at(x, y, c);
        const double difference = std::abs(a - b);
        const double allowed = (c < 3 ? bound(std::max(a, b)) : 0.0) + half_slack(b);
        result.worst_over_bound = std::max(result.worst_over_bound, difference / allowed);
        result.max_abs = std::max(result.max_abs, difference);
        sum += difference;
        ++count;
      }
    }
  }
  result.mean_abs = sum / static_cast<double>(count);
  return result;
}

TEST(Hdr8, ErodeAndDilateAreExactOnTheStoredValues) {
  // Values on the codes: the chain encodes them exactly, so only half precision differs.
  const ImageF codes = hdr_image(64, 48, true);
  auto on = render(kMorphologyChain, codes, true);
  auto off = render(kMorphologyChain, codes, false);
  ASSERT_TRUE(on.ok()) << on.message();
  ASSERT_TRUE(off.ok()) << off.message();
  for (size_t i = 0; i < on->pixels.size(); ++i)
    ASSERT_LE(std::abs(on->pixels[i] - off->pixels[i]), half_slack(off->pixels[i])) << i;
}

TEST(Hdr8, TheMorphologyChainIsWithinTheEncodingsBound) {
  const ImageF light = hdr_image(64, 48, false);
  auto on = render(kMorphologyChain, light, true);
  auto off = render(kMorphologyChain, light, false);
  ASSERT_TRUE(on.ok()) << on.message();
  ASSERT_TRUE(off.ok()) << off.message();
  const Comparison result = compare(*on, *off);
  EXPECT_GT(result.max_abs, 0.0) << "nothing was encoded";
  EXPECT_LE(result.worst_over_bound, 1.0);
}

// Every window radius (sizes 3 to 9), erosion and dilation, each after an encoded writer.
const char* kWideMorphologyChain = R"({
  "aquarelle": 1,
  "nodes": {
    "input": {"type": "image_input", "params": {"name": "image"}},
    "first": {"type": "dilate", "params": {"size": 3}, "inputs": {"image": "input.image"}},
    "e5": {"type": "erode", "params": {"size": 5}, "inputs": {"image": "first.image"}},
    "d7": {"type": "dilate", "params": {"size": 7}, "inputs": {"image": "e5.image"}},
    "e9": {"type": "erode", "params": {"size": 9}, "inputs": {"image": "d7.image"}},
    "d3": {"type": "dilate", "params": {"size": 3}, "inputs": {"image": "e9.image"}}
  },
  "output": "d3.image"
})";

// The morphology's blocked path (morphology.glsl: 2 x 2 blocks of packed 8-bit row extremes)
// takes the extremes of the same stored values as the plain row and column passes, so the
// images are the same bits, at even and odd sizes (the last block half outside the image).
TEST(Hdr8, TheBlockedMorphologyGivesTheSameBitsAsThePlainPasses) {
  for (const char* graph_text : {kMorphologyChain, kWideMorphologyChain}) {
    // The readers after the first node get an encoded 8-bit input: the blocked path's case.
    const Plan plan = plan_of(read_graph_text(graph_text, registry(), "chain"), "half");
    ASSERT_FALSE(plan.nodes.empty());
    for (const PlannedNode& node : plan.nodes) {
      if (node.id != "input" && node.id != plan.nodes.back().id) {
        EXPECT_EQ(stored(plan, node.id), uint32_t{AQ_FORMAT_RGBA8_HDR_BLOCKS}) << node.id;
      }
    }
    for (const auto& [width, height] : {std::pair{64, 48}, {63, 47}, {17, 9}}) {
      const ImageF light = hdr_image(width, height, false);
      auto plain = render_without("AQUARELLE_MORPH_BLOCKED", graph_text, light);
      // Another image in between: the nodes keep their outputs (damage tracking), so the same
      // input again would be answered with the plain passes' pixels without drawing.
      ASSERT_TRUE(render(graph_text, hdr_image(width, height, true), true).ok());
      auto blocked = render(graph_text, light, true);
      // Pixels between the nodes instead of 2 x 2 blocks (the blocked path within each node).
      ASSERT_TRUE(render(graph_text, hdr_image(width, height, true), true).ok());
      auto pixels_between = render_without("AQUARELLE_MORPH_BLOCKS", graph_text, light);
      ASSERT_TRUE(plain.ok()) << plain.message();
      ASSERT_TRUE(blocked.ok()) << blocked.message();
      ASSERT_TRUE(pixels_between.ok()) << pixels_between.message();
      EXPECT_EQ(test::max_abs_diff(*blocked, *plain), 0.0) << width << "x" << height;
      EXPECT_EQ(test::max_abs_diff(*blocked, *pixels_between), 0.0) << width << "x" << height;
      EXPECT_GT(test::max_abs_diff(*blocked, light), 0.0) << "the windows moved nothing";
    }
  }
}

// A disc and a luminance order between square windows: those nodes work on pixels, so they
// unpack the 2 x 2 blocks they are given and pack the ones they hand on; the bits stay those of
// pixels between every node.
const char* kMixedMorphologyChain = R"({
  "aquarelle": 1,
  "nodes": {
    "input": {"type": "image_input", "params": {"name": "image"}},
    "square": {"type": "erode", "params": {"size": 3}, "inputs": {"image": "input.image"}},
    "disc": {"type": "dilate", "params": {"size": 5, "footprint": "disc"},
             "inputs": {"image": "square.image"}},
    "luma": {"type": "erode", "params": {"size": 3, "mode": "luminance"},
             "inputs": {"image": "disc.image"}},
    "same": {"type": "dilate", "params": {"size": 1}, "inputs": {"image": "luma.image"}},
    "last": {"type": "dilate", "params": {"size": 3}, "inputs": {"image": "same.image"}}
  },
  "output": "last.image"
})";

TEST(Hdr8, NodesThatWorkOnPixelsTakeAndGiveBlocksWithTheSameBits) {
  const Plan plan =
      plan_of(read_graph_text(kMixedMorphologyChain, registry(), "mixed chain"), "half");
  for (const char* id : {"square", "disc", "luma", "same"})
    EXPECT_EQ(stored(plan, id), uint32_t{AQ_FORMAT_RGBA8_HDR_BLOCKS}) << id;
  for (const auto& [width, height] : {std::pair{64, 48}, {33, 19}}) {
    const ImageF light = hdr_image(width, height, false);
    auto pixels = render_without("AQUARELLE_MORPH_BLOCKS", kMixedMorphologyChain, light);
    ASSERT_TRUE(render(kMixedMorphologyChain, hdr_image(width, height, true), true).ok());
    auto blocks = render(kMixedMorphologyChain, light, true);
    ASSERT_TRUE(pixels.ok()) << pixels.message();
    ASSERT_TRUE(blocks.ok()) << blocks.message();
    EXPECT_EQ(test::max_abs_diff(*blocks, *pixels), 0.0) << width << "x" << height;
    EXPECT_GT(test::max_abs_diff(*blocks, light), 0.0) << "the windows moved nothing";
  }
}

// wobble takes the erode's 2 x 2 blocks and reads its four texels from them: the same bytes as
// from pixels, so the same light (bit-exact on llvmpipe, whose texel and unpack conversions
// agree; a GPU may round the bytes' floats by an ulp). Unmoved (strength 0) it draws the blocks
// out as pixels instead of passing them through to readers that take pixels: the same light up
// to the float rounding of its bilinear weights at the pixel centres, which can move the half
// output by its last bit.
TEST(Hdr8, WobbleReadsBlocksAsItReadsPixels) {
  const Plan plan = plan_of(read_graph_text(kWobble, registry(), "wobble"), "half");
  EXPECT_EQ(stored(plan, "erode"), uint32_t{AQ_FORMAT_RGBA8_HDR_BLOCKS});
  for (const char* strength : {"8.0", "0.0"}) {
    std::string graph = kWobble;
    graph.replace(graph.find("8.0"), 3, strength);
    const ImageF light = hdr_image(63, 47, false);
    auto pixels = render_without("AQUARELLE_MORPH_BLOCKS", graph.c_str(), light);
    auto blocks = render(graph.c_str(), light, true);
    ASSERT_TRUE(pixels.ok()) << pixels.message();
    ASSERT_TRUE(blocks.ok()) << blocks.message();
    for (size_t i = 0; i < pixels->pixels.size(); ++i)
      ASSERT_LE(std::abs(blocks->pixels[i] - pixels->pixels[i]), half_slack(pixels->pixels[i]))
          << "strength " << strength << ", value " << i;
    EXPECT_GT(test::max_abs_diff(*blocks, light), 0.0) << "nothing was filtered";
  }
}

// A tint to black at 0.5 halves what it reads (on the GPU: undecoded codes would be far off)
// through its own pass (unfused) or as the input of a fused chain.
TEST(Hdr8, AnEncodedImagePassedThroughIsDecodedForItsReader) {
  const ImageF light = hdr_image(64, 48, false);
  // Blocks off: the size-1 erode passes its encoded input through. On: it unpacks its input's
  // 2 x 2 blocks into the working format its reader needs.
  for (bool fuse : {false, true}) {
    for (bool blocks : {false, true}) {
      if (!blocks) setenv("AQUARELLE_MORPH_BLOCKS", "0", 1);
      auto on = render(kPassThrough, light, true, fuse);
      unsetenv("AQUARELLE_MORPH_BLOCKS");
      auto off = render(kPassThrough, light, false, fuse);
      ASSERT_TRUE(on.ok()) << on.message();
      ASSERT_TRUE(off.ok()) << off.message();
      for (ImageF* image : {&*on, &*off})
        for (size_t i = 0; i < image->pixels.size(); i += 4)
          for (size_t c = 0; c < 3; ++c) image->pixels[i + c] *= 2.0f;
      const Comparison result = compare(*on, *off);
      EXPECT_GT(result.max_abs, 0.0) << "nothing was encoded";
      EXPECT_LE(result.worst_over_bound, 1.0) << "an encoded image reached the tint undecoded";
    }
  }
}

// wobble mixes four decoded texels as the hardware's bilinear filter mixes four half ones: the
// mix of values each within the bound of the largest is within that bound.
TEST(Hdr8, WobbleDecodesBeforeItMixes) {
  const ImageF light = hdr_image(64, 48, false);
  auto on = render(kWobble, light, true);
  auto off = render(kWobble, light, false);
  ASSERT_TRUE(on.ok()) << on.message();
  ASSERT_TRUE(off.ok()) << off.message();
  const Comparison result = compare(*on, *off);
  EXPECT_GT(result.max_abs, 0.0) << "nothing was encoded";
  EXPECT_LE(result.max_abs, bound(6.0) + half_slack(6.0));
  // Mixing codes instead of light would be off by a quarter of the value between dark and
  // bright texels; decoded first, the mean error is that of the rounding alone.
  EXPECT_LT(result.mean_abs, 0.01);
}

// A blur mixes values each within the bound of the largest, and the separable kernel stores its
// rows encoded again: twice the bound of the brightest texel at most.
TEST(Hdr8, BlurDecodesEveryTap) {
  const ImageF light = hdr_image(64, 48, false);
  for (const char* kernel : {"separable", "full"}) {
    const std::string graph = pigment_blur(kernel);
    EXPECT_EQ(stored(plan_of(read_graph_text(graph, registry(), "blur"), "half"), "pigment"),
              uint32_t{AQ_FORMAT_RGBA8_HDR});
    auto on = render(graph.c_str(), light, true);
    auto off = render(graph.c_str(), light, false);
    ASSERT_TRUE(on.ok()) << on.message();
    ASSERT_TRUE(off.ok()) << off.message();
    const Comparison result = compare(*on, *off);
    EXPECT_GT(result.max_abs, 0.0) << kernel << ": nothing was encoded";
    EXPECT_LE(result.max_abs, 2.0 * bound(6.0) + half_slack(6.0)) << kernel;
    EXPECT_LT(result.mean_abs, 0.01) << kernel;
  }
}

// The separable kernel's rows pass writes 2 x 2 blocks (blur_direct_separable.frag) and its
// columns pass reads two rows a read: the same taps summed in the same order and stored as the
// same bytes, so the same bits as rows in pixels, also where the windows run over the edges
// (odd sizes, images thinner than the window).
TEST(Hdr8, TheBlursRowsInBlocksGiveTheSameBitsAsInPixels) {
  const std::string graph = pigment_blur("separable");
  for (const auto& [width, height] :
       {std::pair{64, 48}, {63, 47}, {17, 9}, {1, 1}, {9, 1}, {1, 9}, {3, 5}}) {
    const ImageF light = hdr_image(width, height, false);
    auto pixels = render_without("AQUARELLE_BLUR_BLOCKS", graph.c_str(), light);
    // Another image in between, so that no output kept from the render before answers this one.
    ASSERT_TRUE(render(graph.c_str(), hdr_image(width, height, true), true).ok());
    auto blocks = render(graph.c_str(), light, true);
    ASSERT_TRUE(pixels.ok()) << pixels.message();
    ASSERT_TRUE(blocks.ok()) << blocks.message();
    EXPECT_EQ(test::max_abs_diff(*blocks, *pixels), 0.0) << width << "x" << height;
    if (width * height > 1) {
      EXPECT_GT(test::max_abs_diff(*blocks, light), 0.0) << "the blur moved nothing";
    }
  }
}

// The flagship's chain wobble → edge → pigment_apply → blur: at final the wobble's draw runs
// edge and pigment_apply as its epilogue and encodes the result; in a proxy render the host's
// fused pass (edge and pigment_apply) encodes it. Either way the blur decodes every tap: within
// twice the bound of the brightest texel, as for a blur alone.
std::string flagship_chain() {
  return wobble_edge_pigment_graph(
      nlohmann::json::object(), "blur",
      {{"type", "blur"},
       {"params", {{"sigma", 2.0}, {"depth_weight", 0.5}, {"radial_weight", 0.35}}}});
}

TEST(Hdr8, TheEpilogueAndTheFusedPassEncodeWhatTheyWrite) {
  const ImageF light = hdr_image(64, 48, false);
  const std::string graph = flagship_chain();
  for (const char* quality : {"final", "preview"}) {
    ReadResult read = read_graph_text(graph, registry(), "flagship chain");
    read.graph.settings.quality = quality;
    const Plan plan = plan_of(read, "half");
    // At final the wobble writes the chain's result in 2 x 2 blocks for the blur's rows pass
    // (epilogue_blocks_test); the host's fused pass writes encoded pixels.
    EXPECT_EQ(stored(plan, "pigment"), std::string(quality) == "final"
                                           ? uint32_t{AQ_FORMAT_RGBA8_HDR_BLOCKS}
                                           : uint32_t{AQ_FORMAT_RGBA8_HDR})
        << quality;
    const PlannedPass* pass = plan.pass_of("pigment");
    ASSERT_NE(pass, nullptr);
    EXPECT_EQ(pass->epilogue, std::string(quality) == "final") << quality;
    EXPECT_GE(pass->chain.size(), 2u) << quality;
    auto on = render(graph.c_str(), light, true, true, quality);
    auto off = render(graph.c_str(), light, false, true, quality);
    ASSERT_TRUE(on.ok()) << on.message();
    ASSERT_TRUE(off.ok()) << off.message();
    const Comparison result = compare(*on, *off);
    EXPECT_GT(result.max_abs, 0.0) << quality << ": nothing was encoded";
    EXPECT_LE(result.max_abs, 2.0 * bound(6.0) + half_slack(6.0)) << quality;
    EXPECT_LT(result.mean_abs, 0.01) << quality;
  }
}

}  // namespace
}  // namespace aq::test
