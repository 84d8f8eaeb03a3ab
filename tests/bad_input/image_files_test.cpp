// Hostile and unusual image files (issue 17, items 2, 8 and 10): a 1 KB PNG whose header
// says 16384x16384 (4.4 GB before failing), the memory budget, NaN and Inf that a blur would
// spread over the whole picture, CMYK+alpha TIFFs (inks were used as RGB), an EXR whose data
// window is offset in its display window (came out as a bare 10x10 image), a path with a NUL
// character (the part before it was read), and messages for missing files, symlink loops
// and names that are too long.
#include <aquarelle/core/color.h>
#include <aquarelle/core/image_io.h>

#include <cmath>
#include <cstdlib>
#include <fstream>
#include <iterator>
#include <limits>

#include "bad_input/bad_input_support.h"

namespace aq::test::bad_input {
namespace {

bool mentions(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}

const ColorConfig& config() {
  static Result<ColorConfig> loaded = ColorConfig::load();
  EXPECT_TRUE(loaded.ok()) << loaded.message();
  return *loaded;
}

// Item 2.
TEST(ImageDeclaredSizes, KilobytePngDeclaring16384SquaredIsRefusedBeforeAllocating) {
  const fs::path dir = scratch_dir("bad_input_png_huge");
  std::string ihdr = big_endian(16384) + big_endian(16384) + std::string("\x08\x06\x00\x00\x00", 5);
  std::string png = std::string("\x89PNG\r\n\x1a\n", 8) + png_chunk("IHDR", ihdr) +
                    png_chunk("IDAT", std::string(900, '\0')) + png_chunk("IEND", "");
  write_bytes(dir / "huge.png", png);
  ASSERT_LT(fs::file_size(dir / "huge.png"), 1100u);
  auto image = read_image((dir / "huge.png").string(), config());
  ASSERT_FALSE(image.ok());
  EXPECT_TRUE(mentions(image.message(), "huge.png")) << image.message();
  EXPECT_TRUE(mentions(image.message(), "16384x16384")) << image.message();
  EXPECT_TRUE(mentions(image.message(), "cannot be stored")) << image.message();
}

// Found by the image fuzzer: 27 bytes of EXR header declaring a 1.8 GB attribute, which
// OpenEXR allocated before OIIO returned. Named .png: the EXR is found by its magic number.
TEST(ImageDeclaredSizes, ExrAttributeLargerThanTheFileIsRefused) {
  const fs::path dir = scratch_dir("bad_input_exr_attribute");
  const unsigned char bytes[] = {0x76, 0x2f, 0x31, 0x01, 0x02, 0x00, 0x00, 0x00, 0x1c,
                                 0x00, 0x00, 0x00, 0x3a, 0x49, 0x6d, 0x61, 0x67, 0x65,
                                 0x48, 0x69, 0x05, 0x42, 0x4d, 0x73, 0x5a, 0x00, 0x74};
  for (const char* name : {"forged.exr", "forged.png"}) {
    write_bytes(dir / name, std::string(reinterpret_cast<const char*>(bytes), sizeof(bytes)));
    auto image = read_image((dir / name).string(), config());
    ASSERT_FALSE(image.ok()) << name;
    EXPECT_TRUE(mentions(image.message(), name)) << image.message();
    EXPECT_TRUE(mentions(image.message(), "1833515520 bytes")) << image.message();
  }
}

// Found by the image fuzzer: an EXR whose channel list does not end within its declared size.
// OpenEXR reads a channel list up to its empty name, whatever the size says, so it read past
// it and took later bytes as a 2 GB string attribute.
TEST(ImageDeclaredSizes, ExrChannelListRunningPastItsSizeIsRefused) {
  const fs::path dir = scratch_dir("bad_input_exr_chlist");
  auto little = [](uint32_t v) {
    return std::string{static_cast<char>(v), static_cast<char>(v >> 8), static_cast<char>(v >> 16),
                       static_cast<char>(v >> 24)};
  };
  const std::string channel =
      std::string("R\0", 2) + little(1) + std::string(4, '\0') + little(1) + little(1);
  const std::string list = channel + std::string("G\0", 2);  // no empty name before the end
  const std::string exr = std::string("\x76\x2f\x31\x01\x02\x00\x00\x00", 8) +
                          std::string("channels\0chlist\0", 16) + little(list.size()) + list +
                          std::string(64, '\x7f') + std::string(1, '\0');
  write_bytes(dir / "chlist.exr", exr);
  auto image = read_image((dir / "chlist.exr").string(), config());
  ASSERT_FALSE(image.ok());
  EXPECT_TRUE(mentions(image.message(), "chlist.exr")) << image.message();
  EXPECT_TRUE(mentions(image.message(), "'channels'")) << image.message();
  EXPECT_TRUE(mentions(image.message(), "channel list")) << image.message();
}

// Found by the image fuzzer: a 320-byte PNG whose second text chunk declares 1.9 GB; libpng
// reserved it before reading, past the fuzzer's 1 GB limit. A well-formed PNG with text
// chunks still reads.
TEST(ImageDeclaredSizes, PngChunkLongerThanTheFileIsRefused) {
  const fs::path dir = scratch_dir("bad_input_png_chunk");
  const std::string ihdr = big_endian(4) + big_endian(3) + std::string("\x08\x02\x00\x00\x00", 5);
  const std::string head = std::string("\x89PNG\r\n\x1a\n", 8) + png_chunk("IHDR", ihdr) +
                           png_chunk("tEXt", std::string("Comment\0fine", 12));
  const std::string forged = big_endian(0x70670067u) + "tEXt" + "Software" + std::string(40, 'x');
  write_bytes(dir / "forged.png", head + forged);
  auto refused = read_image((dir / "forged.png").string(), config());
  ASSERT_FALSE(refused.ok());
  EXPECT_TRUE(mentions(refused.message(), "forged.png")) << refused.message();
  EXPECT_TRUE(mentions(refused.message(), "'tEXt'")) << refused.message();
  EXPECT_TRUE(mentions(refused.message(), "1885798503 bytes")) << refused.message();

  ASSERT_TRUE(write_image((dir / "fine.png").string(), constant_image(4, 3, 0.5f, 0.25f, 1.0f),
                          WriteOptions{false, 8})
                  .ok());
  auto fine = read_image((dir / "fine.png").string(), config());
  ASSERT_TRUE(fine.ok()) << fine.message();
  EXPECT_EQ(fine->width, 4);
  EXPECT_EQ(fine->height, 3);
}

// A 4x3 JPEG written by OpenImageIO, to put forged segments into.
std::string fine_jpeg(const fs::path& dir) {
  EXPECT_TRUE(write_image((dir / "fine.jpg").string(), constant_image(4, 3, 0.5f, 0.25f, 1.0f),
                          WriteOptions{false, 8})
                  .ok());
  std::ifstream in(dir / "fine.jpg", std::ios::binary);
  const std::string fine((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  EXPECT_GT(fine.size(), 2u);
  EXPECT_EQ(fine.substr(0, 2), std::string("\xff\xd8", 2));
  return fine;
}

std::string jpeg_segment(char marker, const std::string& data) {
  return std::string("\xff", 1) + marker + static_cast<char>((data.size() + 2) >> 8) +
         static_cast<char>((data.size() + 2) & 0xff) + data;
}

// An APP13 segment whose IPTC resource declares 99 bytes and a record 94, in 58 bytes.
std::string forged_iptc_segment() {
  const std::string resource = std::string("8BIM\x04\x04\x00\x00", 8) + big_endian(99) +
                               std::string("\x1c\x02\x41\x00\x5e", 5) + std::string(25, 'x');
  return jpeg_segment('\xed', std::string("Photoshop 3.0\0", 14) + resource);
}

// Reads `fine` with `inserted` right after its SOI marker: refused with a message naming the
// file and `what`, while the fine file still reads.
void expect_refused_after_soi(const fs::path& dir, const std::string& fine,
                              const std::string& inserted, const std::string& what) {
  write_bytes(dir / "forged.jpg", fine.substr(0, 2) + inserted + fine.substr(2));
  auto refused = read_image((dir / "forged.jpg").string(), config());
  ASSERT_FALSE(refused.ok());
  EXPECT_TRUE(mentions(refused.message(), "forged.jpg")) << refused.message();
  EXPECT_TRUE(mentions(refused.message(), what)) << refused.message();
  auto read = read_image((dir / "fine.jpg").string(), config());
  ASSERT_TRUE(read.ok()) << read.message();
  EXPECT_EQ(read->width, 4);
}

// Found by the image fuzzer: a JPEG whose Photoshop/IPTC segment (APP13) is 58 bytes long while
// its IPTC resource declares 99 and a record 94; OpenImageIO 2.4 copied the record from past
// the segment (ASan: heap-buffer-overflow in decode_iptc_iim).
TEST(ImageDeclaredSizes, JpegIptcRecordLongerThanItsSegmentIsRefused) {
  const fs::path dir = scratch_dir("bad_input_jpeg_iptc");
  expect_refused_after_soi(dir, fine_jpeg(dir), forged_iptc_segment(), "APP13");
}

// Found by the image fuzzer in CI (2026-12-05) after the check above: the same overflow behind
// bytes that are no marker. libjpeg skips such garbage (a segment whose length was made shorter
// leaves some) and reads on; the check stopped its walk there and let the file through.
TEST(ImageDeclaredSizes, JpegIptcRecordBehindGarbageIsRefused) {
  const fs::path dir = scratch_dir("bad_input_jpeg_iptc_garbage");
  const std::string fine = fine_jpeg(dir);
  const std::string comment = jpeg_segment('\xfe', "a comment");
  // The comment's length says 4 bytes: the rest of its text is garbage to libjpeg.
  std::string shortened = comment;
  shortened[3] = 4;
  expect_refused_after_soi(dir, fine, shortened + forged_iptc_segment(), "APP13");
  // "FF 00" is a stuffed byte, not a marker; FF runs are fill.
  expect_refused_after_soi(dir, fine, std::string("\xff\x00\xff\xff", 4) + forged_iptc_segment(),
                           "APP13");
}

// OpenImageIO reads the first 8BIM resource's id and size without checking the segment holds
// them, finds the signatures with strcmp, and decodes Exif over the segment's length minus 6,
// an unsigned count that wraps.
TEST(ImageDeclaredSizes, JpegMetadataEndingInsideItsHeaderIsRefused) {
  const fs::path dir = scratch_dir("bad_input_jpeg_short_metadata");
  const std::string fine = fine_jpeg(dir);
  expect_refused_after_soi(dir, fine,
                           jpeg_segment('\xed', std::string("Photoshop 3.0\0"
                                                            "8BIM\x04\x04",
                                                            20)),
                           "first resource");
  expect_refused_after_soi(dir, fine, jpeg_segment('\xe1', std::string("Exif\0", 5)), "Exif");
  // Cut inside the signature: strcmp reads on past the segment.
  expect_refused_after_soi(dir, fine, jpeg_segment('\xe1', "Exif"), "Exif");
  expect_refused_after_soi(dir, fine, jpeg_segment('\xed', "Photoshop 3.0"), "APP13");
}

TEST(ImageDeclaredSizes, MemoryBudgetRefusesLargeDecodes) {
  const fs::path dir = scratch_dir("bad_input_budget");
  ASSERT_TRUE(write_image((dir / "big.exr").string(), constant_image(512, 512, 0.5f, 0.5f, 0.5f),
                          WriteOptions{false, 8})
                  .ok());
  ::setenv("AQUARELLE_MEMORY_BUDGET_MB", "1", 1);
  auto refused = read_image((dir / "big.exr").string(), config());
  ::unsetenv("AQUARELLE_MEMORY_BUDGET_MB");
  ASSERT_FALSE(refused.ok());
  EXPECT_TRUE(mentions(refused.message(), "memory budget")) << refused.message();
  EXPECT_TRUE(mentions(refused.message(), "AQUARELLE_MEMORY_BUDGET_MB")) << refused.message();
  auto read = read_image((dir / "big.exr").string(), config());
  ASSERT_TRUE(read.ok()) << read.message();
}

// Item 8: one NaN and one Inf in the file: replaced on read, counted, and a blur of it stays
// finite everywhere (before: every pixel NaN).
TEST(ImageValues, NanAndInfAreReplacedOnReadAndDoNotSpread) {
  const fs::path dir = scratch_dir("bad_input_nan");
  ImageF input = constant_image(32, 32, 0.25f, 0.5f, 0.75f);
  input.at(10, 12, 0) = std::numeric_limits<float>::quiet_NaN();
  input.at(20, 5, 1) = std::numeric_limits<float>::infinity();
  const std::string path = (dir / "nan.exr").string();
  ASSERT_TRUE(write_image(path, input, WriteOptions{true, 8}).ok());
  ImageReadNotes notes;
  auto read = read_image(path, config(), "", &notes);
  ASSERT_TRUE(read.ok()) << read.message();
  EXPECT_EQ(notes.non_finite_values, 2u);
  EXPECT_TRUE(all_finite(*read));
  EXPECT_EQ(read->at(10, 12, 0), 0.0f);
  EXPECT_FLOAT_EQ(read->at(0, 0, 2), 0.75f);

  nlohmann::json graph = {
      {"aquarelle", 1},
      {"settings", {{"width", 32}, {"height", 32}, {"frames", {1, 1}}, {"precision", "float"}}},
      {"nodes",
       {{"source", {{"type", "read"}, {"params", {{"path", path}}}}},
        {"blur",
         {{"type", "blur"},
          {"params", {{"sigma", 3.0}}},
          {"inputs", {{"image", "source.image"}}}}}}},
      {"output", "blur.image"}};
  auto blurred = render_graph(graph.dump());
  ASSERT_TRUE(blurred.ok()) << blurred.message();
  EXPECT_TRUE(all_finite(*blurred));
  EXPECT_NEAR(blurred->at(0, 31, 2), 0.75, 1e-3) << "far from the replaced pixels";
}

double srgb_to_linear(double v) {
  return v <= 0.04045 ? v / 12.92 : std::pow((v + 0.055) / 1.055, 2.4);
}

TEST(ImageValues, CmykAlphaTiffIsConvertedToRgb) {
  const fs::path dir = scratch_dir("bad_input_cmyka");
  const std::string path = (dir / "cmyka.tif").string();
  auto made = run_command(
      "oiiotool --pattern constant:color=0.2,0.4,0.6,0.1,1.0 4x4 5 "
      "--chnames C,M,Y,K,A --attrib tiff:ColorSpace CMYK -d uint8 -o " +
      path);
  ASSERT_EQ(made.exit_code, 0) << made.output;
  auto read = read_image(path, config());
  ASSERT_TRUE(read.ok()) << read.message();
  // Quantised to 8 bits: C 51, M 102, Y 153, K 26 (of 255); RGB = (1 - ink)(1 - K), sRGB.
  const double k = 1.0 - 26.0 / 255.0;
  const double expected[3] = {srgb_to_linear((1.0 - 51.0 / 255.0) * k),
                              srgb_to_linear((1.0 - 102.0 / 255.0) * k),
                              srgb_to_linear((1.0 - 153.0 / 255.0) * k)};
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(read->at(1, 1, c), expected[c], 2e-3) << c;
  EXPECT_NEAR(read->at(1, 1, 3), 1.0, 1e-6);
}

TEST(ImageValues, ExrDataWindowIsPlacedInItsDisplayWindow) {
  const fs::path dir = scratch_dir("bad_input_datawindow");
  const std::string path = (dir / "window.exr").string();
  auto made = run_command(
      "oiiotool --pattern constant:color=1,0.5,0.25,1 10x10 4 "
      "--origin +20+30 --fullsize 64x64+0+0 -d half -o " +
      path);
  ASSERT_EQ(made.exit_code, 0) << made.output;
  auto read = read_image(path, config());
  ASSERT_TRUE(read.ok()) << read.message();
  ASSERT_EQ(read->width, 64);
  ASSERT_EQ(read->height, 64);
  // Display pixel (x 25, y 35 from the top) is inside the data window; row 0 is the bottom.
  EXPECT_FLOAT_EQ(read->at(25, 63 - 35, 0), 1.0f);
  EXPECT_FLOAT_EQ(read->at(25, 63 - 35, 1), 0.5f);
  EXPECT_FLOAT_EQ(read->at(25, 63 - 35, 3), 1.0f);
  EXPECT_FLOAT_EQ(read->at(20, 63 - 30, 3), 1.0f) << "the data window's first pixel";
  EXPECT_FLOAT_EQ(read->at(19, 63 - 30, 3), 0.0f) << "left of the data window";
  EXPECT_FLOAT_EQ(read->at(0, 0, 3), 0.0f);
  EXPECT_FLOAT_EQ(read->at(30, 63 - 40, 3), 0.0f) << "past the data window";
}

TEST(ImageValues, PathWithANulCharacterIsRefused) {
  const fs::path dir = scratch_dir("bad_input_nul");
  ASSERT_TRUE(write_image((dir / "in.exr").string(), constant_image(4, 4, 1, 1, 1)).ok());
  nlohmann::json graph = {
      {"aquarelle", 1},
      {"settings", {{"width", 4}, {"height", 4}, {"frames", {1, 1}}}},
      {"nodes",
       {{"source",
         {{"type", "read"},
          {"params", {{"path", (dir / "in.exr").string() + std::string("\0x", 2)}}}}}}},
      {"output", "source.image"}};
  auto image = render_graph(graph.dump());
  ASSERT_FALSE(image.ok()) << "the part before the NUL was read";
  EXPECT_TRUE(mentions(image.message(), "NUL")) << image.message();
  EXPECT_TRUE(mentions(image.message(), "'source'")) << image.message();
  EXPECT_TRUE(mentions(image.message(), "'path'")) << image.message();
}

// Item 10: the reason in words, and relative paths explained as the graph file's.
TEST(ImageMessages, MissingLoopAndTooLongSayWhat) {
  const fs::path dir = scratch_dir("bad_input_messages");
  auto missing = read_image((dir / "missing.png").string(), config());
  ASSERT_FALSE(missing.ok());
  EXPECT_TRUE(mentions(missing.message(), "no such file")) << missing.message();
  EXPECT_TRUE(mentions(missing.message(), "graph file's folder")) << missing.message();
  EXPECT_FALSE(mentions(missing.message(), "current directory")) << missing.message();

  fs::create_symlink(dir / "b.png", dir / "a.png");
  fs::create_symlink(dir / "a.png", dir / "b.png");
  auto loop = read_image((dir / "a.png").string(), config());
  ASSERT_FALSE(loop.ok());
  EXPECT_TRUE(mentions(loop.message(), "loop of symbolic links")) << loop.message();

  auto too_long = read_image((dir / (std::string(300, 'n') + ".png")).string(), config());
  ASSERT_FALSE(too_long.ok());
  EXPECT_TRUE(mentions(too_long.message(), "name is too long")) << too_long.message();
}

TEST(ImageMessages, LibpngPrintsNoLineOfItsOwn) {
  const fs::path dir = scratch_dir("bad_input_png_stderr");
  const fs::path png = dir / "broken.png";
  ASSERT_TRUE(write_image(png.string(), gradient_image(16, 16)).ok());
  std::string bytes = file_bytes(png);
  const size_t idat = bytes.find("IDAT");
  ASSERT_NE(idat, std::string::npos);
  bytes[idat + 6] = static_cast<char>(bytes[idat + 6] ^ 0x5A);  // breaks the chunk's CRC
  write_bytes(png, bytes);
  write_bytes(dir / "g.json", R"({"aquarelle": 1,
  "settings": {"width": 16, "height": 16, "frames": [1, 1]},
  "nodes": {"source": {"type": "read", "params": {"path": "broken.png"}}},
  "output": "source.image"})");
  auto result = aquarelle_within(
      60, "render " + (dir / "g.json").string() + " -q -o " + (dir / "out.exr").string());
  EXPECT_EQ(result.exit_code, 1) << result.output;
  EXPECT_TRUE(mentions(result.output, "broken.png")) << result.output;
  EXPECT_FALSE(mentions(result.output, "libpng error")) << result.output;
}

}  // namespace
}  // namespace aq::test::bad_input
