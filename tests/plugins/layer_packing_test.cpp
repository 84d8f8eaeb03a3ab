// The layered node's channel packing (plugins/layered/layer_packing.h): objects whose reach
// cannot meet share a channel, so the number of pass ranges follows how many layers pile up on
// one spot and not the object count; layers that can meet keep their far-to-near order.
#include <gtest/gtest.h>

#include <algorithm>

#include "../../plugins/layered/layer_packing.h"

namespace {

layered::Layer box(int x0, int y0, int x1, int y1) {
  layered::Layer l;
  l.x0 = x0, l.y0 = y0, l.x1 = x1, l.y1 = y1;
  return l;
}

int channels(const std::vector<int>& c) {
  return 1 + *std::max_element(c.begin(), c.end());
}

TEST(LayerPacking, ScatteredObjectsShareOneChannelWhateverTheirCount) {
  for (int count : {4, 16, 64}) {
    std::vector<layered::Layer> layers;
    for (int i = 0; i < count; ++i) {
      const int x = (i % 8) * 160, y = (i / 8) * 90;
      layers.push_back(box(x, y, x + 20, y + 20));
    }
    EXPECT_EQ(channels(layered::assign_channels(layers, 50)), 1) << count << " objects";
  }
}

TEST(LayerPacking, ObjectsOverAFloorTakeTwoChannelsWhateverTheirCount) {
  for (int count : {4, 16, 64}) {
    std::vector<layered::Layer> layers{box(0, 0, 1279, 719)};  // the floor, farthest
    for (int i = 0; i < count; ++i) {
      const int x = (i % 8) * 160, y = (i / 8) * 90;
      layers.push_back(box(x, y, x + 20, y + 20));
    }
    const std::vector<int> c = layered::assign_channels(layers, 50);
    EXPECT_EQ(c[0], 0);
    EXPECT_EQ(channels(c), 2) << count << " objects";
  }
}

TEST(LayerPacking, LayersThatMeetKeepTheirFarToNearOrder) {
  // Three overlapping boxes far to near, and one far away from all.
  const std::vector<layered::Layer> layers{box(0, 0, 40, 40), box(30, 30, 70, 70),
                                           box(60, 0, 90, 40), box(500, 500, 520, 520)};
  const std::vector<int> c = layered::assign_channels(layers, 10);
  EXPECT_LT(c[0], c[1]);
  EXPECT_LT(c[1], c[2]);
  EXPECT_LT(c[0], c[2]);
  EXPECT_EQ(c[3], 0);
  // A negative gap (kernels wider than the image): every layer its own channel.
  const std::vector<int> all = layered::assign_channels(layers, -1);
  EXPECT_EQ(all, (std::vector<int>{0, 1, 2, 3}));
}

TEST(LayerPacking, TheGapCoversBothReaches) {
  EXPECT_EQ(layered::channel_gap(13, 11), 2 * 13 + 2 * 11 + 2);
}

}  // namespace
