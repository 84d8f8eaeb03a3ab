// Tests of the OCIO display/view transform: the CPU path against the sRGB formula, alpha
// handling, error messages, and the GPU path (OCIO's generated GLSL, LUT textures included)
// against the CPU path on a headless EGL context.
#include <aquarelle/core/color.h>
#include <aquarelle/core/display_transform.h>
#include <aquarelle/core/gl_context.h>

#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <random>
#include <sstream>

namespace {

namespace fs = std::filesystem;

double srgb_encode(double linear) {
  return linear <= 0.0031308 ? 12.92 * linear : 1.055 * std::pow(linear, 1.0 / 2.4) - 0.055;
}

// See color_test.cpp: OCIO's continuous sRGB curve is within 6e-5 of the rounded standard.
constexpr double kEncodedTolerance = 6e-5;
// GPU (llvmpipe, float32) against OCIO's CPU processor on the analytic sRGB curve.
constexpr double kGpuTolerance = 1e-5;

aq::ColorConfig shipped_config() {
  unsetenv("OCIO");
  auto config = aq::ColorConfig::load();
  EXPECT_TRUE(config.ok()) << config.message();
  return std::move(config).value();
}

aq::DisplayTransform make_transform(const aq::ColorConfig& config, const std::string& view) {
  auto transform = aq::DisplayTransform::create(config, "sRGB", view);
  EXPECT_TRUE(transform.ok()) << transform.message();
  return std::move(transform).value();
}

aq::ImageF random_premultiplied(int w, int h, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> colour(-0.05f, 3.0f);
  std::uniform_real_distribution<float> alpha(0.0f, 1.0f);
  aq::ImageF image(w, h, 4);
  for (int i = 0; i < w * h; ++i) {
    const float a = i % 7 == 0 ? 1.0f : (i % 11 == 0 ? 0.0f : alpha(rng));
    for (int c = 0; c < 3; ++c) image.pixels[i * 4 + c] = colour(rng) * a;
    image.pixels[i * 4 + 3] = a;
  }
  return image;
}

double max_abs_diff(const aq::ImageF& a, const aq::ImageF& b) {
  double worst = 0;
  for (size_t i = 0; i < a.pixels.size(); ++i) {
    worst = std::max(worst, static_cast<double>(std::abs(a.pixels[i] - b.pixels[i])));
  }
  return worst;
}

TEST(DisplayTransform, DefaultsAreTheConfigsDisplayAndView) {
  auto config = shipped_config();
  auto transform = aq::DisplayTransform::create(config, "", "");
  ASSERT_TRUE(transform.ok()) << transform.message();
  EXPECT_EQ(transform->display(), "sRGB");
  EXPECT_EQ(transform->view(), "Standard");
  EXPECT_EQ(transform->shader_source().rfind("#version 450 core\n", 0), 0u);
}

TEST(DisplayTransform, StandardViewOnCpuIsTheSrgbEncoding) {
  auto config = shipped_config();
  auto transform = make_transform(config, "Standard");
  const int n = 512;
  aq::ImageF image(n, 1, 4);
  for (int i = 0; i < n; ++i) {
    // Dense near black (the linear piece) and up to 1.
    const double x = std::pow(static_cast<double>(i) / (n - 1), 3.0);
    for (int c = 0; c < 3; ++c) image.at(i, 0, c) = static_cast<float>(x);
    image.at(i, 0, 3) = 1.0f;
  }
  const aq::ImageF linear = image;
  ASSERT_TRUE(transform.apply_cpu(image).ok());
  double worst = 0;
  for (int i = 0; i < n; ++i) {
    worst = std::max(worst, std::abs(image.at(i, 0, 1) - srgb_encode(linear.at(i, 0, 1))));
    EXPECT_EQ(image.at(i, 0, 3), 1.0f);
  }
  EXPECT_LT(worst, kEncodedTolerance);
}

TEST(DisplayTransform, RawViewIsIdentityForOpaquePixels) {
  auto config = shipped_config();
  auto transform = make_transform(config, "Raw");
  aq::ImageF image(2, 1, 4);
  image.pixels = {0.2f, 1.5f, -0.1f, 1.0f, 0.0f, 0.9f, 0.01f, 1.0f};
  const auto original = image.pixels;
  ASSERT_TRUE(transform.apply_cpu(image).ok());
  EXPECT_EQ(image.pixels, original);
}

// The view is defined on straight colour: premultiplied input is divided by alpha first, and
// the output keeps straight alpha (what PNG stores).
TEST(DisplayTransform, PremultipliedInputGivesStraightDisplayOutput) {
  auto config = shipped_config();
  auto transform = make_transform(config, "Standard");
  aq::ImageF image(2, 1, 4);
  image.pixels = {0.18f * 0.5f, 0.5f * 0.5f, 0.0f, 0.5f,   // half-covered
                  0.0f,         0.0f,        0.0f, 0.0f};  // fully transparent
  ASSERT_TRUE(transform.apply_cpu(image).ok());
  EXPECT_NEAR(image.pixels[0], srgb_encode(0.18), kEncodedTolerance);
  EXPECT_NEAR(image.pixels[1], srgb_encode(0.5), kEncodedTolerance);
  EXPECT_NEAR(image.pixels[2], 0.0, 1e-7);
  EXPECT_EQ(image.pixels[3], 0.5f);
  EXPECT_EQ(image.pixels[7], 0.0f);
  EXPECT_NEAR(image.pixels[4], 0.0, 1e-7);
}

TEST(DisplayTransform, UnknownViewListsTheAvailableViews) {
  auto config = shipped_config();
  auto transform = aq::DisplayTransform::create(config, "", "Filmic");
  ASSERT_FALSE(transform.ok());
  EXPECT_NE(transform.message().find("Filmic"), std::string::npos) << transform.message();
  EXPECT_NE(transform.message().find("\"Standard\", \"Raw\""), std::string::npos)
      << transform.message();
}

TEST(DisplayTransform, UnknownDisplayListsTheAvailableDisplays) {
  auto config = shipped_config();
  auto transform = aq::DisplayTransform::create(config, "P3-D65", "Standard");
  ASSERT_FALSE(transform.ok());
  EXPECT_NE(transform.message().find("P3-D65"), std::string::npos) << transform.message();
  EXPECT_NE(transform.message().find("\"sRGB\""), std::string::npos) << transform.message();
}

// ---- GPU -------------------------------------------------------------------------------

class DisplayTransformGpu : public ::testing::Test {
 public:  // the helpers are shared with the OSMesa suite
  static void SetUpTestSuite() {
    auto context = aq::create_headless_context(aq::GlBackend::kEgl);
    ASSERT_TRUE(context.ok()) << context.message();
    context_ = std::move(*context).release();
  }
  static void TearDownTestSuite() {
    delete context_;
    context_ = nullptr;
  }
  void SetUp() override {
    ASSERT_NE(context_, nullptr);
    ASSERT_TRUE(context_->activate());
  }

  static aq::gl::Texture upload(const aq::ImageF& image) {
    aq::gl::Texture texture = aq::gl::make_texture();
    glBindTexture(GL_TEXTURE_2D, texture.get());
    glTexStorage2D(GL_TEXTURE_2D, 1, GL_RGBA32F, image.width, image.height);
    glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
    glTexSubImage2D(GL_TEXTURE_2D, 0, 0, 0, image.width, image.height, GL_RGBA, GL_FLOAT,
                    image.pixels.data());
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    return texture;
  }

  static aq::ImageF download(GLuint texture, int w, int h) {
    aq::ImageF image(w, h, 4);
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    glGetTextureImage(texture, 0, GL_RGBA, GL_FLOAT,
                      static_cast<GLsizei>(image.pixels.size() * sizeof(float)),
                      image.pixels.data());
    return image;
  }

  // Runs `transform` on the GPU and on the CPU over `input`; returns the largest difference.
  static double gpu_cpu_difference(const aq::DisplayTransform& transform, const aq::ImageF& input) {
    aq::gl::Texture source = upload(input);
    auto result = transform.apply(source.get(), input.width, input.height);
    EXPECT_TRUE(result.ok()) << result.message();
    if (!result.ok()) return 1e9;
    EXPECT_EQ(glGetError(), static_cast<GLenum>(GL_NO_ERROR));
    const aq::ImageF gpu = download(result->get(), input.width, input.height);
    aq::ImageF cpu = input;
    EXPECT_TRUE(transform.apply_cpu(cpu).ok());
    return max_abs_diff(gpu, cpu);
  }

  static aq::GlContext* context_;
};

aq::GlContext* DisplayTransformGpu::context_ = nullptr;

TEST_F(DisplayTransformGpu, StandardViewMatchesTheCpuPath) {
  auto config = shipped_config();
  auto transform = make_transform(config, "Standard");
  const aq::ImageF input = random_premultiplied(67, 45, 1);  // odd size: no row padding luck
  const double difference = gpu_cpu_difference(transform, input);
  EXPECT_LT(difference, kGpuTolerance);
  RecordProperty("max_abs_gpu_cpu", (std::ostringstream() << difference).str());
  transform.release_gl();
}

TEST_F(DisplayTransformGpu, RawViewOnlyUnpremultiplies) {
  auto config = shipped_config();
  auto transform = make_transform(config, "Raw");
  aq::ImageF input(2, 1, 4);
  input.pixels = {0.25f, 0.5f, 1.0f, 0.5f, 3.0f, 0.0f, 0.5f, 1.0f};
  aq::gl::Texture source = upload(input);
  auto result = transform.apply(source.get(), 2, 1);
  ASSERT_TRUE(result.ok()) << result.message();
  const aq::ImageF gpu = download(result->get(), 2, 1);
  const std::vector<float> expected = {0.5f, 1.0f, 2.0f, 0.5f, 3.0f, 0.0f, 0.5f, 1.0f};
  for (size_t i = 0; i < expected.size(); ++i) EXPECT_NEAR(gpu.pixels[i], expected[i], 1e-6) << i;
  transform.release_gl();
}

TEST_F(DisplayTransformGpu, LeavesTheCallersGlStateAsItWas) {
  auto config = shipped_config();
  auto transform = make_transform(config, "Standard");
  aq::gl::Framebuffer framebuffer = aq::gl::make_framebuffer();
  aq::gl::Texture target = upload(aq::ImageF(8, 8, 4, 0.0f));
  glBindFramebuffer(GL_FRAMEBUFFER, framebuffer.get());
  glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, target.get(), 0);
  glViewport(1, 2, 3, 4);
  glEnable(GL_BLEND);
  aq::gl::Texture source = upload(aq::ImageF(16, 16, 4, 0.5f));
  auto result = transform.apply(source.get(), 16, 16);
  ASSERT_TRUE(result.ok()) << result.message();
  GLint bound = 0, viewport[4] = {};
  glGetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &bound);
  glGetIntegerv(GL_VIEWPORT, viewport);
  EXPECT_EQ(static_cast<GLuint>(bound), framebuffer.get());
  EXPECT_EQ(viewport[0], 1);
  EXPECT_EQ(viewport[3], 4);
  EXPECT_TRUE(glIsEnabled(GL_BLEND));
  glDisable(GL_BLEND);
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
  // Blending was on for the caller but must not have touched the transform's output.
  const aq::ImageF gpu = download(result->get(), 16, 16);
  EXPECT_NEAR(gpu.pixels[0], srgb_encode(1.0), kEncodedTolerance);  // 0.5 / alpha 0.5 = 1
  transform.release_gl();
}

// A config whose view goes through a 1D LUT file and a 3D LUT file: OCIO's GPU code then
// samples LUT textures, which must be uploaded with the right targets and sampler units.
class LutConfig {
 public:
  LutConfig() {
    dir_ = fs::temp_directory_path() / ("aq_display_lut_" + std::to_string(getpid()));
    fs::create_directories(dir_);
    {
      std::ofstream lut(dir_ / "curve.spi1d");
      lut << "Version 1\nFrom 0.0 1.0\nLength 33\nComponents 1\n{\n";
      for (int i = 0; i < 33; ++i) lut << "  " << std::pow(i / 32.0, 1.0 / 2.2) << "\n";
      lut << "}\n";
    }
    {
      std::ofstream cube(dir_ / "mix.cube");
      const int n = 9;
      cube << "LUT_3D_SIZE " << n << "\n";
      for (int b = 0; b < n; ++b) {
        for (int g = 0; g < n; ++g) {
          for (int r = 0; r < n; ++r) {  // red varies fastest
            const double R = r / (n - 1.0), G = g / (n - 1.0), B = b / (n - 1.0);
            cube << 0.7 * R + 0.3 * G * G << " " << G * (1.0 - 0.2 * B) << " "
                 << 0.5 * B * B + 0.5 * R << "\n";
          }
        }
      }
    }
    std::ifstream in(AQ_SOURCE_DIR "/ocio/config.ocio");
    std::stringstream text;
    text << in.rdbuf();
    std::string config = text.str();
    replace(config, "search_path: \"\"", "search_path: \".\"");
    replace(config, "    - !<View> {name: Raw, colorspace: raw}",
            "    - !<View> {name: Raw, colorspace: raw}\n"
            "    - !<View> {name: Lut, colorspace: lut_display}");
    replace(config, "active_views: [Standard, Raw]", "active_views: [Standard, Raw, Lut]");
    config +=
        "\n  - !<ColorSpace>\n"
        "    name: lut_display\n"
        "    isdata: false\n"
        "    from_scene_reference: !<GroupTransform>\n"
        "      children:\n"
        "        - !<FileTransform> {src: curve.spi1d, interpolation: linear}\n"
        "        - !<FileTransform> {src: mix.cube, interpolation: linear}\n";
    std::ofstream(dir_ / "config.ocio") << config;
  }
  ~LutConfig() { fs::remove_all(dir_); }
  std::string path() const { return (dir_ / "config.ocio").string(); }

 private:
  static void replace(std::string& text, const std::string& from, const std::string& to) {
    const size_t at = text.find(from);
    ASSERT_NE(at, std::string::npos) << from;
    text.replace(at, from.size(), to);
  }
  fs::path dir_;
};

TEST_F(DisplayTransformGpu, LutBasedViewMatchesTheCpuPath) {
  LutConfig lut_config;
  auto config = aq::ColorConfig::load_file(lut_config.path());
  ASSERT_TRUE(config.ok()) << config.message();
  auto transform = make_transform(*config, "Lut");
  EXPECT_NE(transform.shader_source().find("sampler3D"), std::string::npos)
      << "the view should need a 3D LUT texture:\n"
      << transform.shader_source();
  EXPECT_NE(transform.shader_source().find("sampler1D"), std::string::npos)
      << "the view should need a 1D LUT texture:\n"
      << transform.shader_source();
  aq::ImageF input = random_premultiplied(40, 30, 2);
  for (int i = 0; i < 40 * 30; ++i) {  // inside the LUT domain: the interesting part
    float& a = input.pixels[i * 4 + 3];
    a = std::max(a, 0.05f);
    for (int c = 0; c < 3; ++c) {
      float& v = input.pixels[i * 4 + c];
      v = std::clamp(std::abs(v) / 3.0f, 0.0f, 1.0f) * a;
    }
  }
  const double difference = gpu_cpu_difference(transform, input);
  // Hardware (llvmpipe) trilinear filtering against OCIO's CPU interpolation.
  EXPECT_LT(difference, 1e-3);
  RecordProperty("max_abs_gpu_cpu_lut", (std::ostringstream() << difference).str());
  transform.release_gl();
}

// `aquarelle render --gl osmesa` runs the same transform on an OSMesa context. Its own suite,
// after the EGL one has destroyed its context: Mesa's EGL and OSMesa share one GL dispatch,
// and an EGL context that is still "current" after OSMesa ran is not re-bound by
// GlContext::activate() (reported to the core).
TEST(DisplayTransformOsmesa, StandardViewMatchesTheCpuPath) {
  auto osmesa = aq::create_headless_context(aq::GlBackend::kOsmesa);
  ASSERT_TRUE(osmesa.ok()) << osmesa.message();
  ASSERT_TRUE((*osmesa)->activate());
  auto config = shipped_config();
  auto transform = make_transform(config, "Standard");
  const double difference =
      DisplayTransformGpu::gpu_cpu_difference(transform, random_premultiplied(31, 17, 3));
  EXPECT_LT(difference, kGpuTolerance);
  transform.release_gl();
}

}  // namespace
