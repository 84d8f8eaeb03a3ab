// Image files through OpenImageIO. Reading: header checks before any allocation, rows flipped
// so row 0 is the bottom, channels mapped to RGBA, colour converted to the working space with
// OpenColorIO, alpha associated (premultiplied) in linear light. Writing: OIIO encodes into
// memory, then the bytes go to a temporary file beside the target that is renamed over it, so
// a failed write (disk full, unwritable directory) never leaves a partial or truncated image.
#include <aquarelle/core/image_io.h>

#include "color_config_data.h"

#include <OpenImageIO/filesystem.h>
#include <OpenImageIO/imageio.h>

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <filesystem>
#include <string_view>
#include <system_error>

namespace aq {
namespace {

constexpr int kMaxChannels = 64;

std::string lowercase_extension(const std::string& path) {
  std::string ext = std::filesystem::path(path).extension().string();
  if (!ext.empty() && ext[0] == '.') ext.erase(0, 1);
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return ext;
}

std::string errno_text(int error) {
  return std::strerror(error);
}

// OIIO keeps per-thread error text; take it so a later call does not report a stale message.
std::string oiio_error() {
  std::string message = OIIO::geterror();
  return message.empty() ? "no details from OpenImageIO" : message;
}

// OIIO messages may span lines; keep ours on one.
std::string trim(std::string text) {
  while (!text.empty() && (text.back() == '\n' || text.back() == ' ')) text.pop_back();
  for (size_t at = text.find('\n'); at != std::string::npos; at = text.find('\n', at)) {
    text.replace(at, 1, "; ");
  }
  return text;
}

// Where each of R, G, B, A comes from in the file's channels (-1: none).
struct ChannelMap {
  int red = 0, green = 0, blue = 0, alpha = -1;
};

ChannelMap map_channels(const OIIO::ImageSpec& spec) {
  ChannelMap map;
  const int n = spec.nchannels;
  if (n <= 2) {  // grey, or grey + alpha
    map.alpha = n == 2 ? 1 : -1;
    return map;
  }
  const int r = spec.channelindex("R"), g = spec.channelindex("G"), b = spec.channelindex("B");
  if (r >= 0 && g >= 0 && b >= 0) {
    map.red = r;
    map.green = g;
    map.blue = b;
  } else {
    map.red = 0;
    map.green = 1;
    map.blue = 2;
  }
  map.alpha = spec.alpha_channel;
  if (map.alpha < 0) map.alpha = spec.channelindex("A");
  if (map.alpha < 0 && n >= 4 && r < 0) map.alpha = 3;  // unnamed 4th channel: alpha
  return map;
}

bool is_float_type(OIIO::TypeDesc type) {
  return type.basetype == OIIO::TypeDesc::FLOAT || type.basetype == OIIO::TypeDesc::HALF ||
         type.basetype == OIIO::TypeDesc::DOUBLE;
}

// The colour space of a file from its metadata and pixel type, as a name in `config`.
std::string colorspace_from_spec(const OIIO::ImageSpec& spec, const ColorConfig& config) {
  const std::string declared = spec.get_string_attribute("oiio:ColorSpace");
  if (config.has_colorspace(declared)) {
    // OIIO says "Linear" or "sRGB"; report the config's own name for the space (or alias).
    return config.data()->config->getColorSpace(declared.c_str())->getName();
  }
  if (is_float_type(spec.format)) return config.working_space();
  return config.has_colorspace("sRGB") ? "sRGB" : config.working_space();
}

Result<std::unique_ptr<OIIO::ImageInput>> open_input(const std::string& path,
                                                     const OIIO::ImageSpec* hints) {
  std::error_code ec;
  auto status = std::filesystem::status(path, ec);
  if (ec || !std::filesystem::exists(status)) {
    return make_error("cannot read image " + path +
                      ": no such file (check the path; relative paths are relative to the "
                      "current directory)");
  }
  if (std::filesystem::is_directory(status)) {
    return make_error("cannot read image " + path + ": it is a directory, not an image file");
  }
  if (std::filesystem::is_regular_file(status) && std::filesystem::file_size(path, ec) == 0) {
    return make_error("cannot read image " + path +
                      ": the file is empty (0 bytes); re-export or re-download it");
  }
  auto input = OIIO::ImageInput::open(path, hints);
  if (!input) {
    return make_error("cannot read image " + path + ": " + trim(oiio_error()) +
                      " (the file is truncated, corrupt or in a format OpenImageIO cannot read; "
                      "convert it to EXR, PNG, JPEG or TIFF)");
  }
  return input;
}

Status check_spec(const std::string& path, const OIIO::ImageSpec& spec) {
  if (spec.width <= 0 || spec.height <= 0) {
    return make_error("cannot read image " + path + ": it has zero size (" +
                      std::to_string(spec.width) + "x" + std::to_string(spec.height) +
                      "); re-export it with at least one pixel");
  }
  if (spec.width > kMaxImageSide || spec.height > kMaxImageSide) {
    return make_error("cannot read image " + path + ": " + std::to_string(spec.width) + "x" +
                      std::to_string(spec.height) + " is larger than " +
                      std::to_string(kMaxImageSide) + " pixels on a side; downscale it first");
  }
  if (spec.depth > 1) {
    return make_error("cannot read image " + path + ": it is a volume (depth " +
                      std::to_string(spec.depth) + "); only 2D images are supported");
  }
  if (spec.nchannels < 1 || spec.nchannels > kMaxChannels) {
    return make_error("cannot read image " + path + ": it has " + std::to_string(spec.nchannels) +
                      " channels; 1 to " + std::to_string(kMaxChannels) + " are supported");
  }
  return Ok{};
}

}  // namespace

Result<std::string> file_colorspace(const std::string& path, const ColorConfig& config) {
  auto input = open_input(path, nullptr);
  if (!input) return input.error();
  return colorspace_from_spec((*input)->spec(), config);
}

Result<ImageF> read_image(const std::string& path, const ColorConfig& config,
                          const std::string& colorspace_override) {
  // Ask for straight alpha as stored, so colour is linearised before alpha is associated.
  OIIO::ImageSpec hints;
  hints.attribute("oiio:UnassociatedAlpha", 1);
  auto opened = open_input(path, &hints);
  if (!opened) return opened.error();
  auto& input = *opened;
  const OIIO::ImageSpec spec = input->spec();
  if (auto ok = check_spec(path, spec); !ok) return ok.error();

  const std::string colorspace =
      colorspace_override.empty() ? colorspace_from_spec(spec, config) : colorspace_override;
  if (!config.has_colorspace(colorspace)) {
    auto known = config.colorspaces();
    std::string list;
    for (const auto& name : known) list += (list.empty() ? "" : ", ") + name;
    return make_error("cannot read image " + path + " as colour space \"" + colorspace +
                      "\": the OCIO config " + config.path() +
                      " has no such space (known: " + list + ")");
  }

  const int w = spec.width, h = spec.height, n = spec.nchannels;
  const size_t row_floats = static_cast<size_t>(w) * n;
  std::vector<float> file_pixels(row_floats * h);
  // A negative row stride starting at the last row stores the file's top row last: row 0 of
  // the result is the bottom of the picture, as GL expects.
  const auto row_bytes = static_cast<OIIO::stride_t>(row_floats * sizeof(float));
  float* last_row = file_pixels.data() + row_floats * (h - 1);
  if (!input->read_image(0, 0, 0, n, OIIO::TypeDesc::FLOAT, last_row, OIIO::AutoStride,
                         -row_bytes)) {
    std::string reason = trim(input->geterror());
    if (reason.empty()) reason = trim(oiio_error());
    return make_error("cannot read the pixels of image " + path + ": " + reason +
                      " (the file is probably truncated or corrupt; re-export it)");
  }
  const bool straight_alpha = spec.get_int_attribute("oiio:UnassociatedAlpha", 0) != 0;
  input->close();

  const ChannelMap map = map_channels(spec);
  ImageF image(w, h, 4);
  const size_t count = static_cast<size_t>(w) * h;
  for (size_t i = 0; i < count; ++i) {
    const float* src = file_pixels.data() + i * n;
    float* dst = image.pixels.data() + i * 4;
    dst[0] = src[map.red];
    dst[1] = src[map.green];
    dst[2] = src[map.blue];
    dst[3] = map.alpha >= 0 ? src[map.alpha] : 1.0f;
  }
  file_pixels = {};

  if (auto ok = config.to_working(image, colorspace); !ok) {
    return make_error("cannot read image " + path + ": " + ok.message());
  }
  if (straight_alpha && map.alpha >= 0) {
    for (size_t i = 0; i < count; ++i) {
      float* px = image.pixels.data() + i * 4;
      px[0] *= px[3];
      px[1] *= px[3];
      px[2] *= px[3];
    }
  }
  return image;
}

bool is_display_referred_format(const std::string& path) {
  const std::string ext = lowercase_extension(path);
  return ext == "png" || ext == "jpg" || ext == "jpeg" || ext == "tif" || ext == "tiff";
}

namespace {

bool is_linear_format(const std::string& ext) {
  return ext == "exr" || ext == "hdr";
}

Status write_all(int fd, const std::vector<unsigned char>& bytes, const std::string& what) {
  size_t done = 0;
  while (done < bytes.size()) {
    ssize_t n = ::write(fd, bytes.data() + done, bytes.size() - done);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) {
      const int error = n < 0 ? errno : ENOSPC;
      return make_error("cannot write " + what + ": " + errno_text(error) + " after " +
                        std::to_string(done) + " of " + std::to_string(bytes.size()) +
                        " bytes (free disk space or choose another output path)");
    }
    done += static_cast<size_t>(n);
  }
  return Ok{};
}

// Targets that are not regular files (a device, a FIFO) cannot be replaced by a rename; they
// get the bytes directly.
Status write_to_special_file(const std::string& path, const std::vector<unsigned char>& bytes) {
  int fd = ::open(path.c_str(), O_WRONLY | O_CLOEXEC);
  if (fd < 0) return make_error("cannot open " + path + " for writing: " + errno_text(errno));
  Status status = write_all(fd, bytes, path);
  if (::close(fd) != 0 && status.ok()) {
    status = make_error("cannot write " + path + ": " + errno_text(errno));
  }
  return status;
}

Status write_atomically(const std::string& path, const std::string& ext,
                        const std::vector<unsigned char>& bytes) {
  const std::string temp = path + ".tmp-" + std::to_string(::getpid()) + "." + ext;
  int fd = ::open(temp.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0666);
  if (fd < 0) {
    const int error = errno;
    std::string dir = std::filesystem::path(path).parent_path().string();
    if (dir.empty()) dir = ".";
    return make_error("cannot write image " + path + ": cannot create a file in directory " + dir +
                      ": " + errno_text(error) +
                      " (check that the directory exists and is writable)");
  }
  Status status = write_all(fd, bytes, "image " + path);
  if (status.ok() && ::fsync(fd) != 0) {
    status = make_error("cannot write image " + path + ": " + errno_text(errno));
  }
  if (::close(fd) != 0 && status.ok()) {
    status = make_error("cannot write image " + path + ": " + errno_text(errno));
  }
  if (status.ok() && ::rename(temp.c_str(), path.c_str()) != 0) {
    status = make_error("cannot write image " + path + ": renaming " + temp +
                        " over it failed: " + errno_text(errno));
  }
  if (!status.ok()) ::unlink(temp.c_str());
  return status;
}

Result<OIIO::TypeDesc> pixel_type_for(const std::string& path, const std::string& ext,
                                      const WriteOptions& options) {
  if (ext == "exr")
    return OIIO::TypeDesc(options.float_data ? OIIO::TypeDesc::FLOAT : OIIO::TypeDesc::HALF);
  if (ext == "hdr") return OIIO::TypeDesc(OIIO::TypeDesc::FLOAT);
  if (ext == "jpg" || ext == "jpeg") return OIIO::TypeDesc(OIIO::TypeDesc::UINT8);
  if (ext == "png" || ext == "tif" || ext == "tiff") {
    if (options.bits == 8) return OIIO::TypeDesc(OIIO::TypeDesc::UINT8);
    if (options.bits == 16) return OIIO::TypeDesc(OIIO::TypeDesc::UINT16);
    return make_error("cannot write image " + path + ": " + std::to_string(options.bits) +
                      " bits per channel is not supported for ." + ext + "; use 8 or 16");
  }
  return make_error("cannot write image " + path + ": unsupported format \"." + ext +
                    "\"; use .exr (linear half/float), .hdr, .png, .jpg or .tif");
}

}  // namespace

Status write_image(const std::string& path, const ImageF& image, const WriteOptions& options) {
  if (image.width <= 0 || image.height <= 0 || image.empty()) {
    return make_error("cannot write image " + path + ": the image is empty (" +
                      std::to_string(image.width) + "x" + std::to_string(image.height) + ")");
  }
  if (image.channels != 1 && image.channels != 3 && image.channels != 4) {
    return make_error("cannot write image " + path + ": " + std::to_string(image.channels) +
                      " channels; only 1 (grey), 3 (RGB) or 4 (RGBA) can be written");
  }
  if (image.pixels.size() != static_cast<size_t>(image.width) * image.height * image.channels) {
    return make_error("cannot write image " + path +
                      ": pixel buffer size does not match width x height x channels");
  }
  const std::string ext = lowercase_extension(path);
  auto type = pixel_type_for(path, ext, options);
  if (!type) return type.error();

  std::error_code ec;
  auto target_status = std::filesystem::status(path, ec);
  if (!ec && std::filesystem::is_directory(target_status)) {
    return make_error("cannot write image " + path + ": it is a directory; give a file name");
  }

  // JPEG and Radiance HDR have no alpha: drop it by striding over 4 floats while writing 3.
  const bool rgb_only = ext == "jpg" || ext == "jpeg" || ext == "hdr";
  int channels = image.channels;
  if (rgb_only && channels == 4) channels = 3;
  if (ext == "hdr" && channels == 1) {
    return make_error("cannot write image " + path +
                      ": Radiance HDR holds only RGB; write grey images as .exr");
  }
  OIIO::ImageSpec spec(image.width, image.height, channels, *type);
  if (channels == 4) spec.alpha_channel = 3;
  if (!is_linear_format(ext)) {
    // Display-referred pixels arrive with straight alpha; keep OIIO from dividing by alpha.
    spec.attribute("oiio:UnassociatedAlpha", 1);
  }

  std::vector<unsigned char> bytes;
  OIIO::Filesystem::IOVecOutput memory(bytes);
  auto output = OIIO::ImageOutput::create(path, &memory);
  if (!output) {
    return make_error("cannot write image " + path + ": " + trim(oiio_error()) +
                      " (use .exr, .hdr, .png, .jpg or .tif)");
  }
  const auto pixel_bytes = static_cast<OIIO::stride_t>(image.channels * sizeof(float));
  const auto row_bytes = pixel_bytes * image.width;
  const float* last_row =
      image.pixels.data() + static_cast<size_t>(image.width) * image.channels * (image.height - 1);
  if (!output->open(path, spec) ||
      !output->write_image(OIIO::TypeDesc::FLOAT, last_row, pixel_bytes, -row_bytes) ||
      !output->close()) {
    std::string reason = trim(output->geterror());
    if (reason.empty()) reason = trim(oiio_error());
    return make_error("cannot encode image " + path + ": " + reason);
  }
  output.reset();
  if (bytes.empty())
    return make_error("cannot encode image " + path + ": OpenImageIO wrote 0 bytes");

  if (!ec && std::filesystem::exists(target_status) &&
      !std::filesystem::is_regular_file(target_status)) {
    return write_to_special_file(path, bytes);
  }
  return write_atomically(path, ext, bytes);
}

}  // namespace aq

namespace aq {

// Multi-channel EXR (render --layer): one pass per named channel group, as compositors read
// them. Same atomic write as write_image; OpenEXR stores the channels sorted by name.
Status write_exr_channels(const std::string& path, const ImageF& image,
                          const std::vector<std::string>& channel_names,
                          const WriteOptions& options) {
  if (lowercase_extension(path) != "exr") {
    return make_error("cannot write image " + path +
                      ": named channels (layers) need an .exr file; change the extension");
  }
  if (image.width <= 0 || image.height <= 0 || image.channels < 1 ||
      static_cast<size_t>(image.channels) != channel_names.size() ||
      image.pixels.size() != static_cast<size_t>(image.width) * image.height * image.channels) {
    return make_error("cannot write image " + path + ": " + std::to_string(channel_names.size()) +
                      " channel names for an image of " + std::to_string(image.channels) +
                      " channels (" + std::to_string(image.width) + "x" +
                      std::to_string(image.height) + ")");
  }
  OIIO::ImageSpec spec(image.width, image.height, image.channels,
                       options.float_data ? OIIO::TypeDesc::FLOAT : OIIO::TypeDesc::HALF);
  spec.channelnames = channel_names;
  spec.alpha_channel = -1;
  for (size_t c = 0; c < channel_names.size(); ++c) {
    if (channel_names[c] == "A") spec.alpha_channel = static_cast<int>(c);
  }
  std::vector<unsigned char> bytes;
  OIIO::Filesystem::IOVecOutput memory(bytes);
  auto output = OIIO::ImageOutput::create(path, &memory);
  if (!output) return make_error("cannot write image " + path + ": " + trim(oiio_error()));
  const auto pixel_bytes = static_cast<OIIO::stride_t>(image.channels * sizeof(float));
  const auto row_bytes = pixel_bytes * image.width;
  const float* last_row =
      image.pixels.data() + static_cast<size_t>(image.width) * image.channels * (image.height - 1);
  if (!output->open(path, spec) ||
      !output->write_image(OIIO::TypeDesc::FLOAT, last_row, pixel_bytes, -row_bytes) ||
      !output->close()) {
    std::string reason = trim(output->geterror());
    if (reason.empty()) reason = trim(oiio_error());
    return make_error("cannot encode image " + path + ": " + reason);
  }
  output.reset();
  return write_atomically(path, "exr", bytes);
}

}  // namespace aq
