// Tests of the OpenColorIO config: finding the shipped config, $OCIO, the working space, and
// the sRGB conversion against the IEC 61966-2-1 formula (not against OCIO itself).
#include <aquarelle/core/color.h>

#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

namespace {

namespace fs = std::filesystem;

double srgb_encode(double linear) {
  return linear <= 0.0031308 ? 12.92 * linear : 1.055 * std::pow(linear, 1.0 / 2.4) - 0.055;
}
double srgb_decode(double encoded) {
  return encoded <= 0.04045 ? encoded / 12.92 : std::pow((encoded + 0.055) / 1.055, 2.4);
}

// OCIO's ExponentWithLinearTransform joins the two pieces where they meet exactly (break
// 0.0392857, slope 12.9232), the standard rounds them (0.04045, 12.92): the curves differ by
// at most ~5e-5 in encoded value (1/80 of an 8-bit step).
constexpr double kEncodedTolerance = 6e-5;
constexpr double kLinearRelativeTolerance = 3e-4;

class ScopedEnv {
 public:
  ScopedEnv(const char* name, const std::string& value) : name_(name) {
    if (const char* old = std::getenv(name)) old_ = old;
    had_ = std::getenv(name) != nullptr;
    setenv(name, value.c_str(), 1);
  }
  ~ScopedEnv() {
    if (had_) {
      setenv(name_, old_.c_str(), 1);
    } else {
      unsetenv(name_);
    }
  }

 private:
  const char* name_;
  std::string old_;
  bool had_ = false;
};

fs::path temp_dir(const std::string& name) {
  fs::path dir =
      fs::temp_directory_path() / ("aq_color_test_" + std::to_string(getpid()) + "_" + name);
  fs::create_directories(dir);
  return dir;
}

std::string read_text(const fs::path& path) {
  std::ifstream in(path);
  std::stringstream buffer;
  buffer << in.rdbuf();
  return buffer.str();
}

aq::ColorConfig load_shipped() {
  unsetenv("OCIO");
  auto config = aq::ColorConfig::load();
  EXPECT_TRUE(config.ok()) << config.message();
  return std::move(config).value();
}

TEST(ColorConfig, LoadsTheShippedConfigWithoutOcio) {
  auto config = load_shipped();
  EXPECT_EQ(config.working_space(), "lin_rec709");
  EXPECT_EQ(fs::weakly_canonical(config.path()),
            fs::weakly_canonical(AQ_SOURCE_DIR "/ocio/config.ocio"));
  EXPECT_EQ(config.default_display(), "sRGB");
  EXPECT_EQ(config.default_view(), "Standard");
  EXPECT_EQ(config.views(), (std::vector<std::string>{"Standard", "Raw"}));
  EXPECT_EQ(config.views("sRGB"), config.views());
  EXPECT_TRUE(config.has_colorspace("sRGB"));
  EXPECT_TRUE(config.has_colorspace("raw"));
  EXPECT_TRUE(config.has_colorspace("Linear"));  // the name OIIO gives EXR files
  EXPECT_FALSE(config.has_colorspace("no_such_space"));
}

TEST(ColorConfig, SrgbToWorkingMatchesTheStandardFormula) {
  auto config = load_shipped();
  const int n = 1024;
  aq::ImageF image(n, 1, 4);
  for (int i = 0; i < n; ++i) {
    for (int c = 0; c < 3; ++c) image.at(i, 0, c) = static_cast<float>(i) / (n - 1);
    image.at(i, 0, 3) = 0.25f;
  }
  ASSERT_TRUE(config.to_working(image, "sRGB").ok());
  double worst = 0;
  for (int i = 0; i < n; ++i) {
    const double expected = srgb_decode(static_cast<double>(i) / (n - 1));
    for (int c = 0; c < 3; ++c) {
      const double error = std::abs(image.at(i, 0, c) - expected) / std::max(expected, 1e-3);
      worst = std::max(worst, error);
    }
    EXPECT_EQ(image.at(i, 0, 3), 0.25f) << "alpha must be left alone";
  }
  EXPECT_LT(worst, kLinearRelativeTolerance);
}

TEST(ColorConfig, WorkingToSrgbMatchesTheStandardFormula) {
  auto config = load_shipped();
  // Both pieces of the curve: below and above 0.0031308, and the exact break.
  const std::vector<double> values = {0.0,  1e-4, 0.001, 0.003, 0.0031308, 0.004,
                                      0.01, 0.05, 0.18,  0.5,   0.9,       1.0};
  aq::ImageF image(static_cast<int>(values.size()), 1, 3);
  for (size_t i = 0; i < values.size(); ++i) {
    for (int c = 0; c < 3; ++c) image.at(static_cast<int>(i), 0, c) = static_cast<float>(values[i]);
  }
  ASSERT_TRUE(config.from_working(image, "sRGB").ok());
  for (size_t i = 0; i < values.size(); ++i) {
    EXPECT_NEAR(image.at(static_cast<int>(i), 0, 0), srgb_encode(values[i]), kEncodedTolerance)
        << "linear " << values[i];
  }
  // Middle grey encodes to the well-known 0.4614.
  EXPECT_NEAR(image.at(8, 0, 1), 0.46135, 2e-4);
}

TEST(ColorConfig, RawAndWorkingSpacesAreIdentity) {
  auto config = load_shipped();
  aq::ImageF image(3, 1, 4);
  image.pixels = {-0.5f, 0.0f, 2.0f, 1.0f, 100.0f, 0.25f, 1e-6f, 0.5f, 1.0f, 1.0f, 1.0f, 0.0f};
  const auto original = image.pixels;
  ASSERT_TRUE(config.to_working(image, "raw").ok());
  EXPECT_EQ(image.pixels, original);
  ASSERT_TRUE(config.to_working(image, "lin_rec709").ok());
  EXPECT_EQ(image.pixels, original);
}

TEST(ColorConfig, UnknownColorspaceIsAnErrorListingTheKnownOnes) {
  auto config = load_shipped();
  aq::ImageF image(1, 1, 4, 0.5f);
  auto status = config.to_working(image, "ACEScg_missing");
  ASSERT_FALSE(status.ok());
  EXPECT_NE(status.message().find("ACEScg_missing"), std::string::npos) << status.message();
  EXPECT_NE(status.message().find("\"sRGB\""), std::string::npos) << status.message();
  EXPECT_NE(status.message().find("config.ocio"), std::string::npos) << status.message();
}

TEST(ColorConfig, TwoChannelImagesAreRefused) {
  auto config = load_shipped();
  aq::ImageF image(1, 1, 2, 0.5f);
  EXPECT_FALSE(config.to_working(image, "sRGB").ok());
}

TEST(ColorConfig, OcioEnvironmentVariableIsHonoured) {
  const fs::path dir = temp_dir("env");
  std::string text = read_text(AQ_SOURCE_DIR "/ocio/config.ocio");
  const std::string from = "{name: Standard, colorspace: sRGB}";
  ASSERT_NE(text.find(from), std::string::npos);
  text.replace(text.find(from), from.size(), "{name: Gallery, colorspace: sRGB}");
  const std::string active = "active_views: [Standard, Raw]";
  ASSERT_NE(text.find(active), std::string::npos);
  text.replace(text.find(active), active.size(), "active_views: [Gallery, Raw]");
  const fs::path path = dir / "renamed.ocio";
  std::ofstream(path) << text;

  {
    ScopedEnv env("OCIO", path.string());
    auto config = aq::ColorConfig::load();
    ASSERT_TRUE(config.ok()) << config.message();
    EXPECT_EQ(config->path(), path.string());
    EXPECT_EQ(config->views(), (std::vector<std::string>{"Gallery", "Raw"}));
    EXPECT_EQ(config->default_view(), "Gallery");
  }
  auto shipped = aq::ColorConfig::load();
  ASSERT_TRUE(shipped.ok());
  EXPECT_EQ(shipped->default_view(), "Standard");
  fs::remove_all(dir);
}

TEST(ColorConfig, BadOcioPathIsAnErrorNamingTheFileAndTheVariable) {
  ScopedEnv env("OCIO", "/nonexistent/aquarelle/config.ocio");
  auto config = aq::ColorConfig::load();
  ASSERT_FALSE(config.ok());
  EXPECT_NE(config.message().find("/nonexistent/aquarelle/config.ocio"), std::string::npos)
      << config.message();
  EXPECT_NE(config.message().find("$OCIO"), std::string::npos) << config.message();
}

TEST(ColorConfig, MalformedConfigIsAnErrorWithOcioMessage) {
  const fs::path dir = temp_dir("malformed");
  const fs::path path = dir / "broken.ocio";
  std::ofstream(path) << "ocio_profile_version: 2\ncolorspaces: [this is not: valid\n";
  auto config = aq::ColorConfig::load_file(path.string());
  ASSERT_FALSE(config.ok());
  EXPECT_NE(config.message().find(path.string()), std::string::npos) << config.message();
  fs::remove_all(dir);
}

TEST(ColorConfig, ConfigWithoutSceneLinearRoleIsRefused) {
  const fs::path dir = temp_dir("norole");
  std::string text = read_text(AQ_SOURCE_DIR "/ocio/config.ocio");
  const std::string role = "  scene_linear: lin_rec709\n";
  ASSERT_NE(text.find(role), std::string::npos);
  text.erase(text.find(role), role.size());
  const fs::path path = dir / "norole.ocio";
  std::ofstream(path) << text;
  auto config = aq::ColorConfig::load_file(path.string());
  ASSERT_FALSE(config.ok());
  EXPECT_NE(config.message().find("scene_linear"), std::string::npos) << config.message();
  fs::remove_all(dir);
}

}  // namespace
