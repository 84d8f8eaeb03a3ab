// `blur`'s distance_scale is in the depth's units (issue 38, item 4): a scene built at another
// scale, every surface past distance_scale, is blurred at full strength everywhere; rendering
// it warns, naming the parameter and the frame's depths (the background, at the far plane
// 200, counts: the blur treats it as far). A scale that reaches into the scene
// gives no warning.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include <filesystem>
#include <fstream>
#include <string>

#include "app/cli_support.h"

namespace {

namespace fs = std::filesystem;
using aq::test::aquarelle;

// A cube 8 units wide, 40 units from the camera (its front 36 away), its g-buffer blurred with
// depth.
std::string blurred_scene(double distance_scale) {
  nlohmann::json g = {
      {"aquarelle", 1},
      {"settings", {{"width", 32}, {"height", 32}}},
      {"nodes",
       {{"cube",
         {{"type", "object"}, {"params", {{"source", "cube"}, {"scale", {8.0, 8.0, 8.0}}}}}},
        {"join",
         {{"type", "scene_join"},
          {"params", {{"camera_position", {0.0, 0.0, 40.0}}, {"camera_target", {0.0, 0.0, 0.0}}}},
          {"inputs", {{"objects", {"cube.object"}}}}}},
        {"gbuf", {{"type", "gbuffer"}, {"inputs", {{"scene", "join.scene"}}}}},
        {"blur",
         {{"type", "blur"},
          {"params", {{"sigma", 2.0}, {"distance_scale", distance_scale}}},
          {"inputs", {{"image", "gbuf.albedo"}, {"depth", "gbuf.depth"}}}}}}},
      {"output", "blur.image"}};
  return g.dump(2);
}

TEST(BlurScale, WholeFramePastDistanceScaleWarnsWithTheDepths) {
  const fs::path dir = aq::test::scratch_dir("blur_scale");
  std::ofstream(dir / "far.json") << blurred_scene(1.0);
  const auto far =
      aquarelle("render " + (dir / "far.json").string() + " -o " + (dir / "far.exr").string());
  EXPECT_EQ(far.exit_code, 0) << far.output;
  EXPECT_NE(far.output.find("warning"), std::string::npos) << far.output;
  EXPECT_NE(far.output.find("'distance_scale' (1)"), std::string::npos) << far.output;
  EXPECT_NE(far.output.find("whole frame is blurred"), std::string::npos) << far.output;
  EXPECT_NE(far.output.find("depths 36 to 200"), std::string::npos) << far.output;

  std::ofstream(dir / "near.json") << blurred_scene(60.0);
  const auto near =
      aquarelle("render " + (dir / "near.json").string() + " -o " + (dir / "near.exr").string());
  EXPECT_EQ(near.exit_code, 0) << near.output;
  EXPECT_EQ(near.output.find("distance_scale"), std::string::npos) << near.output;
}

}  // namespace
