// `aquarelle render --layer`: node outputs as named layers of one multi-channel EXR, read back
// with OpenImageIO as a compositor would (channel names, top row first) and compared with the
// same outputs rendered on their own through the test harness.
#include <gtest/gtest.h>

#include <OpenImageIO/imageio.h>

#include <algorithm>
#include <cmath>

#include "app/cli_support.h"
#include "support/harness.h"

namespace aq::test {
namespace {

constexpr int kWidth = 96, kHeight = 54, kFrame = 5;

struct ExrFile {
  OIIO::ImageSpec spec;
  std::vector<float> pixels;  // row 0 at the top, as OIIO gives it
  float at(int x, int y, const std::string& channel) const {
    const int c = spec.channelindex(channel);
    return pixels[(static_cast<size_t>(y) * spec.width + x) * spec.nchannels + c];
  }
};

ExrFile read_exr(const std::string& path) {
  ExrFile file;
  auto input = OIIO::ImageInput::open(path);
  if (!input) {
    ADD_FAILURE() << "cannot open " << path << ": " << OIIO::geterror();
    return file;
  }
  file.spec = input->spec();
  file.pixels.resize(static_cast<size_t>(file.spec.width) * file.spec.height * file.spec.nchannels);
  EXPECT_TRUE(
      input->read_image(0, 0, 0, file.spec.nchannels, OIIO::TypeDesc::FLOAT, file.pixels.data()));
  return file;
}

bool has_channel(const ExrFile& file, const std::string& name) {
  return file.spec.channelindex(name) >= 0;
}

// Largest difference between the file's channels and an image rendered by the harness (row 0
// at the bottom): a flipped or shuffled layer fails.
double max_layer_diff(const ExrFile& file, const ImageF& image,
                      const std::vector<std::string>& channels) {
  double worst = 0;
  for (int y = 0; y < file.spec.height; ++y) {
    for (int x = 0; x < file.spec.width; ++x) {
      for (size_t c = 0; c < channels.size(); ++c) {
        const double a = file.at(x, y, channels[c]);
        const double b = image.at(x, file.spec.height - 1 - y, static_cast<int>(c));
        worst = std::max(worst, std::abs(a - b));
      }
    }
  }
  return worst;
}

ImageF render_port(const std::string& port) {
  RenderOptions options;
  options.width = kWidth;
  options.height = kHeight;
  options.frame = kFrame;
  options.output = port;
  auto image = render_graph_file(source_path("graphs/underwater.json"), options);
  EXPECT_TRUE(image.ok()) << image.message();
  return image.ok() ? *image : ImageF();
}

std::string render_args(const std::filesystem::path& out) {
  return "render " + source_path("graphs/underwater.json") + " -q --float --quality final " +
         "--precision float --size " + std::to_string(kWidth) + "x" + std::to_string(kHeight) +
         " --frames " + std::to_string(kFrame) + " -o " + out.string();
}

TEST(ExrLayers, ChosenOutputsAreNamedLayersOfTheFrame) {
  auto dir = scratch_dir("exr_layers");
  auto run = aquarelle(render_args(dir / "out.####.exr") +
                       " --layer gbuf.normal --layer light.image --layer gbuf.depth");
  ASSERT_EQ(run.exit_code, 0) << run.output;
  ExrFile file = read_exr((dir / "out.0005.exr").string());
  ASSERT_EQ(file.spec.width, kWidth);
  ASSERT_EQ(file.spec.height, kHeight);
  for (const char* name : {"R", "G", "B", "A", "normal.X", "normal.Y", "normal.Z", "light.R",
                           "light.G", "light.B", "light.A", "depth.Z"}) {
    EXPECT_TRUE(has_channel(file, name)) << "no channel " << name;
  }
  EXPECT_EQ(file.spec.nchannels, 12);
  if (HasFailure()) return;

  EXPECT_LT(max_layer_diff(file, render_port("gbuf.normal"), {"normal.X", "normal.Y", "normal.Z"}),
            1e-5);
  EXPECT_LT(max_layer_diff(file, render_port("light.image"),
                           {"light.R", "light.G", "light.B", "light.A"}),
            1e-5);
  EXPECT_LT(max_layer_diff(file, render_port("gbuf.depth"), {"depth.Z"}), 1e-4);
  EXPECT_LT(max_layer_diff(file, render_port("tint.image"), {"R", "G", "B", "A"}), 1e-5);
  // Normals are unit vectors somewhere: the layer is not empty.
  double longest = 0;
  for (int y = 0; y < kHeight; ++y) {
    for (int x = 0; x < kWidth; ++x) {
      const double nx = file.at(x, y, "normal.X"), ny = file.at(x, y, "normal.Y"),
                   nz = file.at(x, y, "normal.Z");
      longest = std::max(longest, std::sqrt(nx * nx + ny * ny + nz * nz));
    }
  }
  EXPECT_NEAR(longest, 1.0, 1e-2);
}

TEST(ExrLayers, DisplayOutputGetsItsLayersBesideIt) {
  auto dir = scratch_dir("exr_layers_png");
  auto run = aquarelle(render_args(dir / "out.####.png") + " --layer N=gbuf.normal");
  ASSERT_EQ(run.exit_code, 0) << run.output;
  EXPECT_TRUE(std::filesystem::exists(dir / "out.0005.png"));
  ExrFile file = read_exr((dir / "out.0005.layers.exr").string());
  EXPECT_EQ(file.spec.nchannels, 3);
  EXPECT_TRUE(has_channel(file, "N.X") && has_channel(file, "N.Y") && has_channel(file, "N.Z"));
}

TEST(ExrLayers, BadLayersAreRefusedWithTheNodeAndItsOutputs) {
  auto dir = scratch_dir("exr_layers_bad");
  auto unknown_port = aquarelle(render_args(dir / "out.####.exr") + " --layer gbuf.normals");
  EXPECT_EQ(unknown_port.exit_code, 1);
  EXPECT_NE(unknown_port.output.find("no image output 'normals'"), std::string::npos)
      << unknown_port.output;
  EXPECT_NE(unknown_port.output.find("position, normal, albedo, depth, id"), std::string::npos)
      << unknown_port.output;
  auto unknown_node = aquarelle(render_args(dir / "out.####.exr") + " --layer nothing.image");
  EXPECT_EQ(unknown_node.exit_code, 1);
  EXPECT_NE(unknown_node.output.find("no node 'nothing'"), std::string::npos);
  auto clash = aquarelle(render_args(dir / "out.####.exr") +
                         " --layer gbuf.normal --layer normal=light.image");
  EXPECT_EQ(clash.exit_code, 1);
  EXPECT_NE(clash.output.find("NAME=light.image"), std::string::npos) << clash.output;
  EXPECT_FALSE(std::filesystem::exists(dir / "out.0005.exr"));
}

}  // namespace
}  // namespace aq::test
