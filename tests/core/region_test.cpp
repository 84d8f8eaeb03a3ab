// aq::Region (sdk/region.hpp), the pixel sets of damage tracking, against sets of pixels kept
// one by one: the union stays disjoint and holds exactly the pixels added; dilation and
// coverage are the pixel-wise ones; coarsening only ever adds pixels.
#include <gtest/gtest.h>
#include <aquarelle/sdk/region.hpp>

#include <random>
#include <vector>

namespace {

constexpr int kW = 64, kH = 48;

using Pixels = std::vector<bool>;

Pixels pixels_of(const aq::Region& region) {
  Pixels set(kW * kH, false);
  if (region.all()) return Pixels(kW * kH, true);
  for (const aq::PixelRect& r : region.rects()) {
    for (int y = r.y0; y < r.y1; ++y)
      for (int x = r.x0; x < r.x1; ++x) set[y * kW + x] = true;
  }
  return set;
}

int64_t overlap_count(const aq::Region& region) {
  std::vector<int> hits(kW * kH, 0);
  int64_t twice = 0;
  for (const aq::PixelRect& r : region.rects()) {
    for (int y = r.y0; y < r.y1; ++y)
      for (int x = r.x0; x < r.x1; ++x) twice += ++hits[y * kW + x] > 1 ? 1 : 0;
  }
  return twice;
}

std::vector<aq::PixelRect> random_rects(std::mt19937& rng, int count, int max_side) {
  std::uniform_int_distribution<int> x(0, kW - 1), y(0, kH - 1), side(1, max_side);
  std::vector<aq::PixelRect> rects;
  for (int i = 0; i < count; ++i) {
    const int x0 = x(rng), y0 = y(rng);
    rects.push_back(
        aq::PixelRect{x0, y0, std::min(kW, x0 + side(rng)), std::min(kH, y0 + side(rng))});
  }
  return rects;
}

TEST(Region, TheUnionIsDisjointAndHoldsExactlyThePixelsAdded) {
  std::mt19937 rng(5);
  for (int trial = 0; trial < 50; ++trial) {
    const auto rects = random_rects(rng, 1 + trial % 20, 20);
    Pixels expected(kW * kH, false);
    for (const aq::PixelRect& r : rects) {
      for (int y = r.y0; y < r.y1; ++y)
        for (int x = r.x0; x < r.x1; ++x) expected[y * kW + x] = true;
    }
    aq::Region one_by_one, at_once;
    for (const aq::PixelRect& r : rects) one_by_one.add(r);
    at_once.add(rects);
    EXPECT_EQ(pixels_of(one_by_one), expected);
    EXPECT_EQ(pixels_of(at_once), expected);
    EXPECT_EQ(overlap_count(at_once), 0) << "rects overlap: pixels would be drawn twice";
    int64_t count = 0;
    for (bool p : expected) count += p ? 1 : 0;
    EXPECT_EQ(at_once.area(kW, kH), count);
  }
}

TEST(Region, DilationIsThePixelwiseOneClippedToTheImage) {
  std::mt19937 rng(6);
  for (int trial = 0; trial < 20; ++trial) {
    aq::Region region;
    region.add(random_rects(rng, 4, 10));
    const int rx = trial % 4, ry = (trial / 4) % 3;
    const Pixels before = pixels_of(region);
    Pixels expected(kW * kH, false);
    for (int y = 0; y < kH; ++y)
      for (int x = 0; x < kW; ++x) {
        for (int dy = -ry; dy <= ry; ++dy)
          for (int dx = -rx; dx <= rx; ++dx) {
            const int sx = x + dx, sy = y + dy;
            if (sx >= 0 && sx < kW && sy >= 0 && sy < kH && before[sy * kW + sx])
              expected[y * kW + x] = true;
          }
      }
    EXPECT_EQ(pixels_of(region.dilated(rx, ry, kW, kH)), expected) << rx << " " << ry;
  }
}

// combined(): the pixels of one region in (or not in) another, as a node splits its damage
// between two programs (clouds: the volume's composite where a live cell is near, the image
// through the epilogue elsewhere); everything() stands for the whole image on either side.
TEST(Region, CombinedIsThePixelwiseIntersectionAndDifference) {
  std::mt19937 rng(8);
  for (int trial = 0; trial < 40; ++trial) {
    aq::Region a, b;
    a.add(random_rects(rng, 1 + trial % 7, 24));
    b.add(random_rects(rng, 1 + trial % 5, 24));
    if (trial == 0) a = aq::Region::everything();
    if (trial == 1) b = aq::Region::everything();
    const Pixels pa = pixels_of(a), pb = pixels_of(b);
    Pixels both(kW * kH, false), only_a(kW * kH, false);
    for (int i = 0; i < kW * kH; ++i) {
      both[i] = pa[i] && pb[i];
      only_a[i] = pa[i] && !pb[i];
    }
    const aq::Region in = aq::combined(a, b, true, kW, kH);
    const aq::Region out = aq::combined(a, b, false, kW, kH);
    EXPECT_EQ(pixels_of(in), both) << "trial " << trial;
    EXPECT_EQ(pixels_of(out), only_a) << "trial " << trial;
    EXPECT_EQ(overlap_count(in), 0);
    EXPECT_EQ(overlap_count(out), 0);
  }
}

TEST(Region, CoversAndEverything) {
  aq::Region small = aq::Region::of(aq::PixelRect{2, 2, 6, 6});
  aq::Region big = aq::Region::of(aq::PixelRect{0, 0, 10, 10});
  EXPECT_TRUE(big.covers(small));
  EXPECT_FALSE(small.covers(big));
  EXPECT_TRUE(small.covers(aq::Region()));
  EXPECT_FALSE(big.covers(aq::Region::everything()));
  aq::Region all = aq::Region::everything();
  all.add(small);
  EXPECT_TRUE(all.all());
  small.add(aq::Region::everything());
  EXPECT_TRUE(small.all());
  EXPECT_TRUE(aq::Region().empty());
  EXPECT_FALSE(aq::Region::everything().empty());
}

// Past kMaxRects (storage) and kMaxDrawRects (for_drawing) the region grows to a coarser grid:
// more pixels, never fewer, and no more rects than the limit.
TEST(Region, CoarseningOnlyAddsPixels) {
  std::mt19937 rng(7);
  std::vector<aq::PixelRect> specks;
  std::uniform_int_distribution<int> x(0, 4095), y(0, 2047);
  for (int i = 0; i < 3000; ++i) {
    const int x0 = x(rng), y0 = y(rng);
    specks.push_back(aq::PixelRect{x0, y0, x0 + 1, y0 + 1});
  }
  aq::Region region;
  region.add(specks);
  ASSERT_FALSE(region.all());
  EXPECT_LE(region.rects().size(), aq::Region::kMaxRects);
  const aq::Region drawn = region.for_drawing();
  EXPECT_LE(drawn.rects().size(), aq::Region::kMaxDrawRects);
  EXPECT_TRUE(drawn.covers(region));
  for (const aq::PixelRect& s : specks) EXPECT_TRUE(region.covers(aq::Region::of(s)));
  // A few rects are left as they are.
  aq::Region few = aq::Region::of(aq::PixelRect{1, 1, 3, 3});
  few.add(aq::PixelRect{10, 10, 12, 12});
  EXPECT_EQ(few.for_drawing().area(kW, kH), 8);
}

// for_drawing grows a region only where its rects are close: tiles like those a scene's meshes
// cover (a row of thin blades, a checkered cluster of 8-pixel tiles and a diagonal of specks,
// 172 rects) cut to at most kMaxDrawRects by merging the closest first (1.35 times the pixels
// here), not by snapping every rect out to a grid (2.35 times).
TEST(Region, ForDrawingMergesTheClosestRects) {
  std::vector<aq::PixelRect> tiles;
  for (int i = 0; i < 40; ++i) tiles.push_back(aq::PixelRect{24 * i, 0, 24 * i + 8, 64});
  for (int j = 0; j < 8; ++j) {
    for (int i = 0; i < 10; ++i) {
      const int x = 100 + 16 * i + 8 * (j % 2), y = 200 + 8 * j;
      tiles.push_back(aq::PixelRect{x, y, x + 8, y + 8});
    }
  }
  for (int i = 0; i < 52; ++i)
    tiles.push_back(aq::PixelRect{8 * i, 300 + 8 * i, 8 * i + 8, 308 + 8 * i});
  aq::Region region;
  region.add(tiles);
  const aq::Region drawn = region.for_drawing();
  EXPECT_LE(drawn.rects().size(), aq::Region::kMaxDrawRects);
  EXPECT_TRUE(drawn.covers(region));
  EXPECT_LT(drawn.area(kW, kH), 3 * region.area(kW, kH) / 2)
      << region.rects().size() << " rects of " << region.area(kW, kH) << " pixels drawn as "
      << drawn.rects().size() << " of " << drawn.area(kW, kH);
}

// A pass over 2 x 2 blocks draws blocks_of(pixels).for_drawing(), whose merged rects also cover
// blocks between the damaged ones: whole_blocks must name every pixel it draws, or the pass that
// reads its output sizes its own input pass too small and reads what nothing wrote this call
// (the morphology chain did, at 1280 x 720 with more than 64 damaged rects).
TEST(Region, WholeBlocksHoldEveryPixelAPassOverTheirBlocksDraws) {
  std::mt19937 rng(11);
  aq::Region region;
  region.add(random_rects(rng, 400, 2));
  const aq::Region blocks = aq::blocks_of(region);
  ASSERT_GT(blocks.rects().size(), aq::Region::kMaxDrawRects)
      << "no merge: the test proves nothing";
  const aq::Region drawn_blocks = blocks.for_drawing();
  aq::Region drawn_pixels;
  for (const aq::PixelRect& b : drawn_blocks.rects()) {
    drawn_pixels.add(
        aq::PixelRect{2 * b.x0, 2 * b.y0, std::min(2 * b.x1, kW), std::min(2 * b.y1, kH)});
  }
  const aq::Region whole = aq::whole_blocks(region, kW, kH);
  EXPECT_EQ(pixels_of(whole), pixels_of(drawn_pixels));
  EXPECT_TRUE(whole.covers(region));
  EXPECT_TRUE(aq::whole_blocks(aq::Region::everything(), kW, kH).all());
}

}  // namespace
