// `object`'s `swim_forward` (issue 38, item 3): a model built along z swims nose first with
// `swim_forward` +z, where the swim loop used to assume +x and swam it sideways; its body wave
// bends it across z. Seen from above through the g-buffer's ids.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include <unistd.h>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>

#include "support/harness.h"

namespace {

namespace fs = std::filesystem;
using aq::ImageF;

// A bar 0.1 wide, 0.1 high and 0.8 long along z, its nose (a narrow tip) at +z.
std::string bar_along_z() {
  std::string text;
  const double x = 0.05, y = 0.05, z = 0.4;
  for (int i = 0; i < 8; ++i) {
    text += "v " + std::to_string(i & 1 ? x : -x) + " " + std::to_string(i & 2 ? y : -y) + " " +
            std::to_string(i & 4 ? z : -z) + "\n";
  }
  text += "f 1 3 4 2\nf 5 6 8 7\nf 1 2 6 5\nf 3 7 8 4\nf 1 5 7 3\nf 2 4 8 6\n";  // a closed box
  return text;
}

nlohmann::json graph(const std::string& path, const std::string& forward, double wave) {
  nlohmann::json params = {{"path", path},      {"animation", "swim"}, {"swim_radius", 0.6},
                           {"swim_speed", 1.0}, {"swim_wave", wave},   {"swim_phase", 0.0}};
  if (!forward.empty()) params["swim_forward"] = forward;
  return {{"aquarelle", 1},
          {"nodes",
           {{"bar", {{"type", "object"}, {"params", params}}},
            {"join",
             {{"type", "scene_join"},
              {"params",
               {{"camera_position", {0.0, 3.0, 0.01}},
                {"camera_target", {0.0, 0.0, 0.0}},
                {"fov", 45.0},
                {"environment", "none"}}},
              {"inputs", {{"objects", {"bar.object"}}}}}},
            {"gbuf", {{"type", "gbuffer"}, {"inputs", {{"scene", "join.scene"}}}}}}},
          {"output", "gbuf.id"}};
}

// Extent of the object's pixels along image x and image y (world x and z seen from above).
std::pair<int, int> extent(const ImageF& id) {
  int x0 = id.width, x1 = -1, y0 = id.height, y1 = -1;
  for (int y = 0; y < id.height; ++y) {
    for (int x = 0; x < id.width; ++x) {
      if (id.at(x, y, 0) != 1.0f) continue;
      x0 = std::min(x0, x), x1 = std::max(x1, x), y0 = std::min(y0, y), y1 = std::max(y1, y);
    }
  }
  return {x1 - x0 + 1, y1 - y0 + 1};
}

ImageF render(const nlohmann::json& g) {
  aq::test::RenderOptions options;
  options.width = options.height = 96;
  options.output = "gbuf.id";
  auto image = aq::test::render_graph(g.dump(), options);
  EXPECT_TRUE(image.ok()) << (image.ok() ? "" : image.message());
  return image.ok() ? *image : ImageF();
}

TEST(SwimForward, AModelAlongZSwimsNoseFirst) {
  const fs::path dir = fs::temp_directory_path() / ("aq_swim_forward_" + std::to_string(getpid()));
  fs::create_directories(dir);
  std::ofstream(dir / "bar.obj") << bar_along_z();
  const std::string path = (dir / "bar.obj").string();
  // At time 0 and phase 0 the loop is at +x of the origin heading +z: a bar heading the way it
  // swims lies along z (image y), one swimming sideways along x.
  const auto [wide_x, long_y] = extent(render(graph(path, "+z", 0.0)));
  EXPECT_GT(long_y, 3 * wide_x) << "+z forward: the bar lies along its direction of travel";
  const auto [side_x, side_y] = extent(render(graph(path, "", 0.0)));
  EXPECT_GT(side_x, 3 * side_y) << "+x forward (the default) turns a z-bar across its path";
  const auto [back_x, back_y] = extent(render(graph(path, "-z", 0.0)));
  EXPECT_GT(back_y, 3 * back_x) << "-z forward: along the path too";
  // The body wave bends the bar sideways (across z), widening it, and never lengthens it.
  const auto [bent_x, bent_y] = extent(render(graph(path, "+z", 0.3)));
  EXPECT_GT(bent_x, wide_x + 1);
  EXPECT_LE(bent_y, long_y + 1);
  fs::remove_all(dir);
}

// A tapered body 1 long with its nose at +0.5 along x, turned so the nose points along
// `forward`: exact coordinate swaps, so the four files hold the same body.
std::string body_along(const std::string& forward) {
  std::string text;
  const int rings = 10, sides = 6;
  for (int i = 0; i <= rings; ++i) {
    const double x = -0.5 + double(i) / rings, r = 0.02 + 0.08 * (1.0 - std::abs(x - 0.2));
    for (int j = 0; j < sides; ++j) {
      const double a = 6.283185307179586 * j / sides;
      double v[3] = {x, r * std::cos(a), 0.6 * r * std::sin(a)};
      const double z = v[2];
      if (forward == "-x") v[0] = -x, v[2] = -z;
      if (forward == "+z") v[0] = -z, v[2] = x;
      if (forward == "-z") v[0] = z, v[2] = -x;
      char line[96];
      std::snprintf(line, sizeof(line), "v %.9g %.9g %.9g\n", v[0], v[1], v[2]);
      text += line;
    }
  }
  for (int i = 0; i < rings; ++i) {
    for (int j = 0; j < sides; ++j) {
      const int a = i * sides + j + 1, b = i * sides + (j + 1) % sides + 1;
      text += "f " + std::to_string(a) + " " + std::to_string(b) + " " + std::to_string(b + sides) +
              "\nf " + std::to_string(a) + " " + std::to_string(b + sides) + " " +
              std::to_string(a + sides) + "\n";
    }
  }
  return text;
}

// The body built along any axis, with that swim_forward, swims exactly as the body built along
// +x with +x: same place, same heading, and the body wave bent to the same side at the same
// time (it bent to the mirrored side for -x and +z).
TEST(SwimForward, EveryAxisSwimsAsTheSameBodyBuiltAlongX) {
  const fs::path dir = fs::temp_directory_path() / ("aq_swim_axes_" + std::to_string(getpid()));
  fs::create_directories(dir);
  auto positions = [&](const std::string& forward) {
    const fs::path path = dir / ("body" + std::to_string(forward[0] == '+') + forward[1] + ".obj");
    std::ofstream(path) << body_along(forward);
    nlohmann::json g = graph(path.string(), forward, 0.3);
    g["output"] = "gbuf.position";
    aq::test::RenderOptions options;
    options.width = options.height = 96;
    options.frame = 5;
    options.output = "gbuf.position";
    auto image = aq::test::render_graph(g.dump(), options);
    EXPECT_TRUE(image.ok()) << (image.ok() ? "" : image.message());
    return image.ok() ? *image : ImageF();
  };
  const ImageF along_x = positions("+x");
  ASSERT_EQ(along_x.width, 96);
  int covered = 0;
  for (int i = 0; i < 96 * 96; ++i) covered += along_x.pixels[4 * i + 3] == 1.0f;
  ASSERT_GT(covered, 100);
  for (const char* forward : {"-x", "+z", "-z"}) {
    const ImageF other = positions(forward);
    ASSERT_EQ(other.width, 96);
    int differing = 0;
    for (int i = 0; i < 96 * 96 * 4; ++i) {
      differing += std::abs(other.pixels[i] - along_x.pixels[i]) > 1e-4f;
    }
    EXPECT_EQ(differing, 0) << "swim_forward " << forward;
  }
  fs::remove_all(dir);
}

}  // namespace
