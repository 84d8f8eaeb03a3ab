// Tests of image reading and writing: round trips per format and bit depth, the sRGB decode
// against its formula, grey and alpha-less files, row order checked against a hand-written
// PPM (top row first by definition), straight alpha in PNG, and every error case with a
// message that names the file.
#include <aquarelle/core/color.h>
#include <aquarelle/core/image_io.h>

#include <gtest/gtest.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cmath>
#include <csignal>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <random>
#include <string>

namespace {

namespace fs = std::filesystem;

double srgb_decode(double encoded) {
  return encoded <= 0.04045 ? encoded / 12.92 : std::pow((encoded + 0.055) / 1.055, 2.4);
}

class ImageIo : public ::testing::Test {
 protected:
  void SetUp() override {
    unsetenv("OCIO");
    auto config = aq::ColorConfig::load();
    ASSERT_TRUE(config.ok()) << config.message();
    config_ = std::make_unique<aq::ColorConfig>(std::move(config).value());
    dir_ = fs::temp_directory_path() /
           ("aq_image_io_test_" + std::to_string(getpid()) + "_" +
            ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }

  std::string path(const std::string& name) const { return (dir_ / name).string(); }
  const aq::ColorConfig& config() const { return *config_; }

  // Files left in the test directory other than `expected` (temporary files must never stay).
  std::vector<std::string> leftovers(const std::vector<std::string>& expected = {}) const {
    std::vector<std::string> found;
    for (const auto& entry : fs::directory_iterator(dir_)) {
      const std::string name = entry.path().filename().string();
      if (std::find(expected.begin(), expected.end(), name) == expected.end()) {
        found.push_back(name);
      }
    }
    return found;
  }

  static aq::ImageF random_image(int w, int h, int channels, float lo, float hi, unsigned seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> dist(lo, hi);
    aq::ImageF image(w, h, channels);
    for (auto& v : image.pixels) v = dist(rng);
    return image;
  }

  std::unique_ptr<aq::ColorConfig> config_;
  fs::path dir_;
};

void expect_error_naming(const aq::Status& status, const std::string& path,
                         const std::string& reason_fragment) {
  ASSERT_FALSE(status.ok()) << "expected an error for " << path;
  EXPECT_NE(status.message().find(path), std::string::npos) << status.message();
  EXPECT_NE(status.message().find(reason_fragment), std::string::npos) << status.message();
}

double max_abs_diff(const aq::ImageF& a, const aq::ImageF& b, int channels) {
  double worst = 0;
  for (int y = 0; y < a.height; ++y) {
    for (int x = 0; x < a.width; ++x) {
      for (int c = 0; c < channels; ++c) {
        worst = std::max(worst, static_cast<double>(std::abs(a.at(x, y, c) - b.at(x, y, c))));
      }
    }
  }
  return worst;
}

TEST_F(ImageIo, ExrFloatRoundTripIsExact) {
  // Scene-linear data: negative, above 1, tiny.
  aq::ImageF image = random_image(64, 48, 4, -2.0f, 40.0f, 1);
  image.at(0, 0, 0) = 1e-30f;
  const std::string file = path("float.exr");
  ASSERT_TRUE(aq::write_image(file, image, {.float_data = true}).ok());
  auto back = aq::read_image(file, config());
  ASSERT_TRUE(back.ok()) << back.message();
  ASSERT_EQ(back->width, 64);
  ASSERT_EQ(back->height, 48);
  ASSERT_EQ(back->channels, 4);
  EXPECT_EQ(back->pixels, image.pixels);
  EXPECT_EQ(*aq::file_colorspace(file, config()), "lin_rec709");
}

TEST_F(ImageIo, ExrHalfRoundTripIsWithinHalfPrecision) {
  aq::ImageF image = random_image(64, 64, 4, 0.0f, 8.0f, 2);
  const std::string file = path("half.exr");
  ASSERT_TRUE(aq::write_image(file, image).ok());
  auto back = aq::read_image(file, config());
  ASSERT_TRUE(back.ok()) << back.message();
  double worst_relative = 0;
  for (size_t i = 0; i < image.pixels.size(); ++i) {
    const double v = image.pixels[i];
    worst_relative = std::max(worst_relative, std::abs(back->pixels[i] - v) / std::max(v, 1e-2));
  }
  EXPECT_LE(worst_relative, 1.0 / 2048.0);  // half: 11 significant bits, rounded
  EXPECT_GT(worst_relative, 0.0) << "the file should hold half, not float";
  EXPECT_LT(fs::file_size(file), 64u * 64 * 4 * sizeof(float))
      << "a half EXR is smaller than the float data";
}

// Display-referred values written to an 8-bit PNG come back linearised: the decode of the
// nearest 8-bit code, by the IEC 61966-2-1 formula.
TEST_F(ImageIo, Png8BitStoresDisplayValuesAndReadsThemBackLinear) {
  aq::ImageF display = random_image(32, 32, 4, 0.0f, 1.0f, 3);
  for (int i = 0; i < 32 * 32; ++i) display.pixels[i * 4 + 3] = 1.0f;
  const std::string file = path("eight.png");
  ASSERT_TRUE(aq::write_image(file, display).ok());
  EXPECT_EQ(*aq::file_colorspace(file, config()), "sRGB");

  auto raw = aq::read_image(file, config(), "raw");
  ASSERT_TRUE(raw.ok()) << raw.message();
  EXPECT_LE(max_abs_diff(*raw, display, 4), 0.5 / 255 + 1e-6);

  auto linear = aq::read_image(file, config());
  ASSERT_TRUE(linear.ok()) << linear.message();
  double worst = 0;
  for (size_t i = 0; i < display.pixels.size(); ++i) {
    if (i % 4 == 3) continue;
    const double code = std::round(display.pixels[i] * 255.0) / 255.0;
    worst = std::max(worst, std::abs(linear->pixels[i] - srgb_decode(code)));
  }
  EXPECT_LT(worst, 1e-4);
}

TEST_F(ImageIo, Png16BitKeepsSixteenBitsOfPrecision) {
  aq::ImageF display = random_image(32, 32, 3, 0.0f, 1.0f, 4);
  const std::string file = path("sixteen.png");
  ASSERT_TRUE(aq::write_image(file, display, {.bits = 16}).ok());
  auto raw = aq::read_image(file, config(), "raw");
  ASSERT_TRUE(raw.ok()) << raw.message();
  const double error = max_abs_diff(*raw, display, 3);
  EXPECT_LE(error, 0.5 / 65535 + 1e-7);
  // An 8-bit file could not do better than 1/510 on random values.
  EXPECT_LT(error, 1e-4);
  // Round trip through the colour conversion: decode then encode gives the stored values back.
  auto linear = aq::read_image(file, config());
  ASSERT_TRUE(linear.ok());
  ASSERT_TRUE(config().from_working(*linear, "sRGB").ok());
  EXPECT_LT(max_abs_diff(*linear, display, 3), 1e-5);
}

TEST_F(ImageIo, Tiff16AndTiff8RoundTrip) {
  aq::ImageF display = random_image(20, 10, 4, 0.0f, 1.0f, 5);
  for (int i = 0; i < 200; ++i) display.pixels[i * 4 + 3] = 1.0f;
  for (int bits : {8, 16}) {
    const std::string file = path("t" + std::to_string(bits) + ".tif");
    ASSERT_TRUE(aq::write_image(file, display, {.bits = bits}).ok());
    auto raw = aq::read_image(file, config(), "raw");
    ASSERT_TRUE(raw.ok()) << raw.message();
    EXPECT_LE(max_abs_diff(*raw, display, 4), 0.5 / ((1 << bits) - 1) + 1e-6) << bits;
  }
}

TEST_F(ImageIo, JpegIsLossyButCloseAndHasNoAlpha) {
  aq::ImageF display(64, 64, 4);
  for (int y = 0; y < 64; ++y) {
    for (int x = 0; x < 64; ++x) {
      display.at(x, y, 0) = x / 63.0f;
      display.at(x, y, 1) = y / 63.0f;
      display.at(x, y, 2) = 0.5f;
      display.at(x, y, 3) = 0.3f;  // dropped: JPEG has no alpha
    }
  }
  const std::string file = path("smooth.jpg");
  ASSERT_TRUE(aq::write_image(file, display).ok());
  auto raw = aq::read_image(file, config(), "raw");
  ASSERT_TRUE(raw.ok()) << raw.message();
  EXPECT_LT(max_abs_diff(*raw, display, 3), 0.05);
  EXPECT_EQ(raw->at(10, 10, 3), 1.0f);
}

TEST_F(ImageIo, HdrKeepsLinearDataWithinRgbePrecision) {
  aq::ImageF image = random_image(16, 16, 3, 0.1f, 50.0f, 6);
  const std::string file = path("radiance.hdr");
  ASSERT_TRUE(aq::write_image(file, image).ok());
  auto back = aq::read_image(file, config());
  ASSERT_TRUE(back.ok()) << back.message();
  for (int y = 0; y < 16; ++y) {
    for (int x = 0; x < 16; ++x) {
      float brightest = std::max({image.at(x, y, 0), image.at(x, y, 1), image.at(x, y, 2)});
      for (int c = 0; c < 3; ++c) {
        // RGBE: 8-bit mantissas sharing the exponent of the brightest channel.
        EXPECT_NEAR(back->at(x, y, c), image.at(x, y, c), brightest / 128.0) << x << "," << y;
      }
      EXPECT_EQ(back->at(x, y, 3), 1.0f);
    }
  }
}

TEST_F(ImageIo, HdrDropsAlphaAndRefusesGrey) {
  const std::string file = path("alpha.hdr");
  ASSERT_TRUE(aq::write_image(file, aq::ImageF(4, 4, 4, 0.5f)).ok());
  auto back = aq::read_image(file, config());
  ASSERT_TRUE(back.ok()) << back.message();
  EXPECT_NEAR(back->at(1, 1, 0), 0.5, 0.5 / 128);
  EXPECT_EQ(back->at(1, 1, 3), 1.0f);
  const std::string grey = path("grey.hdr");
  expect_error_naming(aq::write_image(grey, aq::ImageF(4, 4, 1, 0.5f)), grey, ".exr");
}

TEST_F(ImageIo, GreyFileBecomesRgbWithOpaqueAlpha) {
  aq::ImageF grey(8, 4, 1);
  for (int y = 0; y < 4; ++y) {
    for (int x = 0; x < 8; ++x) grey.at(x, y, 0) = (x + 8 * y) / 31.0f;
  }
  const std::string file = path("grey.png");
  ASSERT_TRUE(aq::write_image(file, grey).ok());
  auto back = aq::read_image(file, config(), "raw");
  ASSERT_TRUE(back.ok()) << back.message();
  ASSERT_EQ(back->channels, 4);
  for (int y = 0; y < 4; ++y) {
    for (int x = 0; x < 8; ++x) {
      for (int c = 0; c < 3; ++c) EXPECT_NEAR(back->at(x, y, c), grey.at(x, y, 0), 0.5 / 255);
      EXPECT_EQ(back->at(x, y, 3), 1.0f);
    }
  }
}

TEST_F(ImageIo, RgbFileWithoutAlphaGetsOpaqueAlpha) {
  aq::ImageF rgb = random_image(5, 7, 3, 0.0f, 4.0f, 7);
  const std::string file = path("rgb.exr");
  ASSERT_TRUE(aq::write_image(file, rgb, {.float_data = true}).ok());
  auto back = aq::read_image(file, config());
  ASSERT_TRUE(back.ok()) << back.message();
  for (int y = 0; y < 7; ++y) {
    for (int x = 0; x < 5; ++x) {
      for (int c = 0; c < 3; ++c) EXPECT_EQ(back->at(x, y, c), rgb.at(x, y, c));
      EXPECT_EQ(back->at(x, y, 3), 1.0f);
    }
  }
}

// A plain PPM lists its TOP row first: that fixes the orientation independently of our writer.
TEST_F(ImageIo, RowZeroIsTheBottomRowOfThePicture) {
  const std::string file = path("rows.ppm");
  std::ofstream(file) << "P3\n2 3\n255\n"
                      << "255 0 0   255 0 0\n"   // top: red
                      << "0 255 0   0 255 0\n"   // middle: green
                      << "0 0 255   0 0 255\n";  // bottom: blue
  auto image = aq::read_image(file, config(), "raw");
  ASSERT_TRUE(image.ok()) << image.message();
  ASSERT_EQ(image->width, 2);
  ASSERT_EQ(image->height, 3);
  EXPECT_EQ(image->at(0, 0, 2), 1.0f) << "row 0 must be the bottom (blue) row";
  EXPECT_EQ(image->at(0, 0, 0), 0.0f);
  EXPECT_EQ(image->at(1, 1, 1), 1.0f);
  EXPECT_EQ(image->at(1, 2, 0), 1.0f) << "the last row must be the top (red) row";

  // And the writer keeps that orientation: PNG written then read matches, row by row.
  const std::string png = path("rows.png");
  ASSERT_TRUE(aq::write_image(png, *image).ok());
  auto back = aq::read_image(png, config(), "raw");
  ASSERT_TRUE(back.ok());
  EXPECT_EQ(back->pixels, image->pixels);
}

// PNG stores straight alpha; the reader associates it after linearising the colour.
TEST_F(ImageIo, PngAlphaIsStraightInTheFileAndAssociatedInMemory) {
  aq::ImageF display(1, 1, 4);
  display.pixels = {0.6f, 0.2f, 1.0f, 0.5f};
  const std::string file = path("alpha.png");
  ASSERT_TRUE(aq::write_image(file, display, {.bits = 16}).ok());
  // Read raw: the file's straight values, premultiplied by the reader.
  auto raw = aq::read_image(file, config(), "raw");
  ASSERT_TRUE(raw.ok()) << raw.message();
  EXPECT_NEAR(raw->pixels[0], 0.6 * 0.5, 1e-4);
  EXPECT_NEAR(raw->pixels[2], 1.0 * 0.5, 1e-4);
  EXPECT_NEAR(raw->pixels[3], 0.5, 1e-4);
  auto linear = aq::read_image(file, config());
  ASSERT_TRUE(linear.ok());
  EXPECT_NEAR(linear->pixels[0], srgb_decode(0.6) * 0.5, 1e-4);
  EXPECT_NEAR(linear->pixels[1], srgb_decode(0.2) * 0.5, 1e-4);
  EXPECT_NEAR(linear->pixels[3], 0.5, 1e-4);
}

TEST_F(ImageIo, ColorspaceOverrideIsUsedAndCheckedAgainstTheConfig) {
  aq::ImageF display(2, 2, 3, 0.5f);
  const std::string file = path("override.png");
  ASSERT_TRUE(aq::write_image(file, display).ok());
  auto as_linear = aq::read_image(file, config(), "lin_rec709");
  ASSERT_TRUE(as_linear.ok());
  EXPECT_NEAR(as_linear->pixels[0], 128.0 / 255.0, 1e-6);
  auto bad = aq::read_image(file, config(), "not_a_space");
  ASSERT_FALSE(bad.ok());
  EXPECT_NE(bad.message().find("not_a_space"), std::string::npos) << bad.message();
  EXPECT_NE(bad.message().find(file), std::string::npos) << bad.message();
}

TEST_F(ImageIo, WritingReplacesAnExistingFileAndLeavesNoTemporaryFile) {
  const std::string file = path("replace.png");
  std::ofstream(file) << "old contents";
  ASSERT_TRUE(aq::write_image(file, aq::ImageF(4, 4, 4, 1.0f)).ok());
  auto back = aq::read_image(file, config());
  ASSERT_TRUE(back.ok()) << back.message();
  EXPECT_EQ(back->width, 4);
  EXPECT_EQ(leftovers({"replace.png"}), std::vector<std::string>{});
}

TEST_F(ImageIo, FormatClassification) {
  for (const char* p : {"a.png", "a.PNG", "dir.x/a.jpg", "a.jpeg", "a.tif", "a.TIFF"}) {
    EXPECT_TRUE(aq::is_display_referred_format(p)) << p;
  }
  for (const char* p : {"a.exr", "a.EXR", "a.hdr", "a", "png", "a.png.exr"}) {
    EXPECT_FALSE(aq::is_display_referred_format(p)) << p;
  }
}

// ---- errors ----------------------------------------------------------------------------

template <typename T>
aq::Status as_status(const aq::Result<T>& result) {
  if (result.ok()) return aq::Ok{};
  return result.error();
}

TEST_F(ImageIo, MissingFileIsAnError) {
  const std::string file = path("nothing_here.png");
  expect_error_naming(as_status(aq::read_image(file, config())), file, "no such file");
}

TEST_F(ImageIo, EmptyFileIsAnError) {
  const std::string file = path("empty.png");
  std::ofstream(file).close();
  expect_error_naming(as_status(aq::read_image(file, config())), file, "empty");
}

TEST_F(ImageIo, ZeroSizeImageIsAnError) {
  const std::string file = path("zero.ppm");
  std::ofstream(file) << "P3\n0 0\n255\n";
  auto result = aq::read_image(file, config());
  ASSERT_FALSE(result.ok());
  EXPECT_NE(result.message().find(file), std::string::npos) << result.message();
}

TEST_F(ImageIo, TruncatedPngIsAnError) {
  const std::string file = path("truncated.png");
  ASSERT_TRUE(aq::write_image(file, random_image(96, 96, 4, 0.0f, 1.0f, 8)).ok());
  fs::resize_file(file, fs::file_size(file) / 2);
  expect_error_naming(as_status(aq::read_image(file, config())), file, "truncated");
}

TEST_F(ImageIo, TruncatedExrIsAnError) {
  const std::string file = path("truncated.exr");
  ASSERT_TRUE(aq::write_image(file, random_image(96, 96, 4, 0.0f, 1.0f, 9)).ok());
  fs::resize_file(file, fs::file_size(file) / 2);
  expect_error_naming(as_status(aq::read_image(file, config())), file, "truncated");
}

// The fuzzer's case: a small EXR whose data window declares 8388612 pixels a row. OpenEXR sized
// its line buffers by it while opening the file; the header walk refuses it first.
TEST_F(ImageIo, ExrDataWindowBeyondTheSideLimitIsRefusedBeforeOpening) {
  const std::string file = path("wide.exr");
  ASSERT_TRUE(aq::write_image(file, random_image(4, 3, 3, 0.0f, 1.0f, 11)).ok());
  std::string bytes;
  {
    std::ifstream in(file, std::ios::binary);
    bytes.assign(std::istreambuf_iterator<char>(in), {});
  }
  const std::string marker("dataWindow\0box2i\0", 17);
  const size_t at = bytes.find(marker);
  ASSERT_NE(at, std::string::npos);
  const int32_t x_max = 8388611;  // xMin 0: 8388612 pixels a row
  std::memcpy(bytes.data() + at + marker.size() + 4 + 8, &x_max, 4);
  std::ofstream(file, std::ios::binary | std::ios::trunc) << bytes;
  const aq::Status read = as_status(aq::read_image(file, config()));
  expect_error_naming(read, file, "8388612x3 data window");
  EXPECT_NE(read.message().find("OpenEXR header"), std::string::npos)
      << "refused by the header walk, before OpenEXR opened the file: " << read.message();
}

TEST_F(ImageIo, CorruptHeaderIsAnError) {
  const std::string file = path("garbage.png");
  std::ofstream(file) << "this is not a png file at all, just text";
  expect_error_naming(as_status(aq::read_image(file, config())), file, "corrupt");
}

TEST_F(ImageIo, HugeImageIsRefusedBeforeAllocating) {
  // The header claims 20000 x 20000 RGB (1.2 GB of bytes, 4.8 GB as float); no pixels follow.
  const std::string file = path("huge.ppm");
  std::ofstream(file, std::ios::binary) << "P6\n20000 20000\n255\n";
  expect_error_naming(as_status(aq::read_image(file, config())), file, "16384");
}

TEST_F(ImageIo, UnsupportedExtensionIsAnErrorOnWrite) {
  const std::string file = path("picture.xyz");
  expect_error_naming(aq::write_image(file, aq::ImageF(2, 2, 4)), file, "unsupported format");
  EXPECT_EQ(leftovers(), std::vector<std::string>{});
}

TEST_F(ImageIo, UnsupportedBitDepthIsAnError) {
  const std::string file = path("twelve.png");
  expect_error_naming(aq::write_image(file, aq::ImageF(2, 2, 4), {.bits = 12}), file, "12");
}

TEST_F(ImageIo, EmptyImageOrOddChannelCountIsAnErrorOnWrite) {
  EXPECT_FALSE(aq::write_image(path("e.png"), aq::ImageF()).ok());
  EXPECT_FALSE(aq::write_image(path("two.png"), aq::ImageF(2, 2, 2)).ok());
  EXPECT_EQ(leftovers(), std::vector<std::string>{});
}

TEST_F(ImageIo, UnwritableDirectoryIsAnErrorNamingThePath) {
  const std::string missing_dir = path("no/such/dir/out.png");
  expect_error_naming(aq::write_image(missing_dir, aq::ImageF(2, 2, 4)), missing_dir,
                      "No such file or directory");
  // Even root cannot create files in /proc.
  const std::string proc = "/proc/aquarelle_test_output.png";
  auto status = aq::write_image(proc, aq::ImageF(2, 2, 4));
  ASSERT_FALSE(status.ok());
  EXPECT_NE(status.message().find(proc), std::string::npos) << status.message();
  if (geteuid() != 0) {  // permission bits do not stop root
    const fs::path locked = dir_ / "locked";
    fs::create_directory(locked);
    fs::permissions(locked, fs::perms::owner_read | fs::perms::owner_exec);
    const std::string file = (locked / "out.png").string();
    expect_error_naming(aq::write_image(file, aq::ImageF(2, 2, 4)), file, "Permission denied");
    fs::permissions(locked, fs::perms::owner_all);
  }
}

TEST_F(ImageIo, DiskFullThroughDevFullIsAnError) {
  // A file name with the real extension that points at /dev/full: every write fails ENOSPC.
  const std::string link = path("full.png");
  fs::create_symlink("/dev/full", link);
  expect_error_naming(aq::write_image(link, aq::ImageF(16, 16, 4, 0.5f)), link,
                      "No space left on device");
  EXPECT_EQ(leftovers({"full.png"}), std::vector<std::string>{});
  EXPECT_TRUE(fs::is_symlink(link)) << "the device link must not be replaced";
}

// A full disk while writing a regular file: the file-size limit makes write(2) fail part way
// (EFBIG). The limit must not touch the test runner, and fork() of a process that already runs
// library threads may deadlock in the child, so the child re-executes this test binary, which
// does the write in kDiskFullChild below (before main) and reports through its exit code.
constexpr const char* kDiskFullChildVariable = "AQ_IMAGE_IO_TEST_DISK_FULL_PATH";

[[maybe_unused]] const bool kDiskFullChild = [] {
  const char* target = std::getenv(kDiskFullChildVariable);
  if (!target) return false;
  aq::ImageF image(128, 128, 4);
  for (size_t i = 0; i < image.pixels.size(); ++i) image.pixels[i] = std::sin(0.37f * i);
  auto status = aq::write_image(target, image, {.float_data = true});
  const bool named = !status.ok() && status.message().find(target) != std::string::npos;
  std::_Exit(status.ok() ? 1 : (named ? 0 : 2));
}();

TEST_F(ImageIo, FailedWriteLeavesNoPartialFileAndKeepsThePreviousOne) {
  const std::string file = path("keep.exr");
  std::ofstream(file) << "previous image";
  // Everything exec needs is built before fork: the child may only make async-signal-safe calls.
  std::string self = fs::read_symlink("/proc/self/exe").string();
  std::vector<std::string> environment = {std::string(kDiskFullChildVariable) + "=" + file};
  for (char** entry = environ; *entry; ++entry) environment.emplace_back(*entry);
  std::vector<char*> envp;
  for (auto& entry : environment) envp.push_back(entry.data());
  envp.push_back(nullptr);
  char* argv[] = {self.data(), nullptr};
  const pid_t child = fork();
  ASSERT_GE(child, 0);
  if (child == 0) {
    std::signal(SIGXFSZ, SIG_IGN);
    rlimit limit{4096, 4096};
    setrlimit(RLIMIT_FSIZE, &limit);
    execve(self.c_str(), argv, envp.data());
    _exit(3);
  }
  int wstatus = 0;
  waitpid(child, &wstatus, 0);
  ASSERT_TRUE(WIFEXITED(wstatus));
  EXPECT_EQ(WEXITSTATUS(wstatus), 0)
      << "1: the write succeeded, 2: the message lacks the path, 3: exec failed";
  std::ifstream in(file);
  std::string contents((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  EXPECT_EQ(contents, "previous image");
  EXPECT_EQ(leftovers({"keep.exr"}), std::vector<std::string>{});
}

TEST_F(ImageIo, WritingOverADirectoryIsAnError) {
  const std::string target = path("adir.png");
  fs::create_directory(target);
  expect_error_naming(aq::write_image(target, aq::ImageF(2, 2, 4)), target, "directory");
}

}  // namespace
