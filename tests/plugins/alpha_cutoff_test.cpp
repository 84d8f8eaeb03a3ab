// `object`'s alpha_cutoff (seed 001's sails: fragments under the cut-off discarded) at the hard
// case the issue names: a texture alpha exactly at the cut-off is kept, one step under it is a
// hole. 204/255 is exactly 0.8; the host stores texels as half floats, where 0.8 is 0.7998.
#include <gtest/gtest.h>

#include <aquarelle/core/image_io.h>

#include <nlohmann/json.hpp>

#include <unistd.h>
#include <filesystem>
#include <string>

#include "support/harness.h"

namespace {

namespace fs = std::filesystem;

// Covered pixels of a card whose texture has alpha code/255 everywhere, cut off at `cutoff`.
int covered(int code, double cutoff) {
  const fs::path dir = fs::temp_directory_path() / ("aq_alpha_cutoff_" + std::to_string(getpid()));
  fs::create_directories(dir);
  const fs::path file = dir / ("alpha_" + std::to_string(code) + ".png");
  aq::ImageF image(4, 4, 4);
  for (int i = 0; i < 16; ++i) {
    for (int c = 0; c < 3; ++c) image.pixels[4 * i + c] = 0.5f;
    image.pixels[4 * i + 3] = static_cast<float>(code / 255.0);
  }
  aq::WriteOptions options;
  options.bits = 8;
  EXPECT_TRUE(aq::write_image(file.string(), image, options).ok());
  nlohmann::json g = {
      {"aquarelle", 1},
      {"nodes",
       {{"card",
         {{"type", "object"},
          {"params", {{"source", "card"}, {"texture", file.string()}, {"alpha_cutoff", cutoff}}}}},
        {"join",
         {{"type", "scene_join"},
          {"params",
           {{"camera_position", {0.0, 0.5, 2.0}},
            {"camera_target", {0.0, 0.5, 0.0}},
            {"environment", "none"}}},
          {"inputs", {{"objects", {"card.object"}}}}}},
        {"gbuf", {{"type", "gbuffer"}, {"inputs", {{"scene", "join.scene"}}}}}}},
      {"output", "gbuf.id"}};
  aq::test::RenderOptions render;
  render.width = render.height = 48;
  render.output = "gbuf.id";
  auto id = aq::test::render_graph(g.dump(), render);
  EXPECT_TRUE(id.ok()) << (id.ok() ? "" : id.message());
  if (!id.ok()) return -1;
  int n = 0;
  for (int i = 0; i < id->width * id->height; ++i) n += id->pixels[i * id->channels] != 0.0f;
  return n;
}

TEST(AlphaCutoff, AlphaExactlyAtTheCutoffIsKeptOneStepUnderIsAHole) {
  const int opaque = covered(255, 0.8);
  EXPECT_GT(opaque, 200);
  EXPECT_EQ(covered(204, 0.8), opaque) << "alpha 204/255 = 0.8, cut-off 0.8: not under it";
  EXPECT_EQ(covered(203, 0.8), 0) << "alpha 203/255 is under 0.8";
  EXPECT_EQ(covered(230, 0.9), opaque) << "230/255 = 0.902 >= 0.9 (the seed's sails)";
  EXPECT_EQ(covered(229, 0.9), 0) << "229/255 = 0.898 < 0.9";
}

}  // namespace
