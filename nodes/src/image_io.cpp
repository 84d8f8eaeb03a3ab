// Image files through OpenImageIO. Reading: header checks before any allocation, rows flipped
// so row 0 is the bottom, channels mapped to RGBA, colour converted to the working space with
// OpenColorIO, alpha associated (premultiplied) in linear light. Writing: OIIO encodes into
// memory, then the bytes go to a temporary file beside the target that is renamed over it, so
// a failed write (disk full, unwritable directory) never leaves a partial or truncated image.
#include <aquarelle/core/image_io.h>

#include <aquarelle/sdk/regular_file.hpp>

#include "color_config_data.h"
#include "image_limits.h"

#include <OpenImageIO/filesystem.h>
#include <OpenImageIO/imageio.h>

#include <fcntl.h>
#include <signal.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <string_view>
#include <system_error>
#include <tuple>

namespace aq {
namespace {

constexpr int kMaxChannels = 64;

// Temporaries are hidden (.NAME.tmp-PID): they never match NAME*.exr or *.exr globs.
constexpr const char* kTemporaryMark = ".tmp-";

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

// libpng prints its own "libpng warning/error: ..." line on stderr before OIIO hands us the
// same reason; our message says it with the path, so the library's line is dropped.
class SilencedStderr {
 public:
  explicit SilencedStderr(bool active) {
    if (!active) return;
    std::fflush(stderr);
    saved_ = ::dup(STDERR_FILENO);
    const int null = ::open("/dev/null", O_WRONLY | O_CLOEXEC);
    if (saved_ < 0 || null < 0 || ::dup2(null, STDERR_FILENO) < 0) restore();
    if (null >= 0) ::close(null);
  }
  ~SilencedStderr() { restore(); }
  SilencedStderr(const SilencedStderr&) = delete;
  SilencedStderr& operator=(const SilencedStderr&) = delete;

 private:
  void restore() {
    if (saved_ < 0) return;
    std::fflush(stderr);
    ::dup2(saved_, STDERR_FILENO);
    ::close(saved_);
    saved_ = -1;
  }
  int saved_ = -1;
};

Result<std::unique_ptr<OIIO::ImageInput>> open_input(const std::string& path,
                                                     const OIIO::ImageSpec* hints) {
  // Only regular files: OIIO's format probe spins on /dev/zero and blocks on a FIFO.
  if (std::string why = files::regular_file_problem(path); !why.empty()) {
    std::string hint =
        " (check the path; a relative path in a graph is relative to the graph "
        "file's folder)";
    if (why.find("regular files") != std::string::npos) hint = "; give the path of an image file";
    return make_error("cannot read image " + path + ": " + why + hint);
  }
  if (files::regular_file_size(path) == 0) {
    return make_error("cannot read image " + path +
                      ": the file is empty (0 bytes); re-export or re-download it");
  }
  // Format probes read a file that no reader recognises, sometimes whole (a 200 GB sparse
  // file named .png): no image this large could be decoded within the budget anyway.
  if (const uint64_t size = files::regular_file_size(path); size > files::memory_budget_bytes()) {
    return make_error("cannot read image " + path + ": it is " + std::to_string(size >> 20) +
                      " MiB, more than the memory budget of " +
                      std::to_string(files::memory_budget_bytes() >> 20) +
                      " MiB (raise AQUARELLE_MEMORY_BUDGET_MB if it is genuine)");
  }
  if (auto ok = check_exr_header(path); !ok) return ok.error();
  if (auto ok = check_png_chunks(path); !ok) return ok.error();
  if (auto ok = check_jpeg_metadata(path); !ok) return ok.error();
  SilencedStderr quiet(lowercase_extension(path) == "png");
  auto input = OIIO::ImageInput::open(path, hints);
  if (!input) {
    return make_error("cannot read image " + path + ": " + trim(oiio_error()) +
                      " (the file is truncated, corrupt or in a format OpenImageIO cannot read; "
                      "convert it to EXR, PNG, JPEG or TIFF)");
  }
  return input;
}

// The picture a file shows is its display window (EXR's may differ from the data window it
// stores); other formats give the same rectangle for both.
struct Window {
  int x = 0, y = 0, width = 0, height = 0;
};

Window display_window(const OIIO::ImageSpec& spec) {
  if (spec.full_width > 0 && spec.full_height > 0) {
    return {spec.full_x, spec.full_y, spec.full_width, spec.full_height};
  }
  return {spec.x, spec.y, spec.width, spec.height};
}

std::string size_text(int w, int h) {
  return std::to_string(w) + "x" + std::to_string(h);
}

Status check_spec(const std::string& path, const OIIO::ImageSpec& spec) {
  const Window shown = display_window(spec);
  if (spec.width <= 0 || spec.height <= 0 || shown.width <= 0 || shown.height <= 0) {
    return make_error("cannot read image " + path + ": it has zero size (" +
                      size_text(spec.width, spec.height) +
                      "); re-export it with at least one pixel");
  }
  for (const auto& [what, w, h] : {std::tuple{"size ", spec.width, spec.height},
                                   std::tuple{"display window ", shown.width, shown.height}}) {
    if (w > kMaxImageSide || h > kMaxImageSide) {
      return make_error("cannot read image " + path + ": its " + what + size_text(w, h) +
                        " is larger than " + std::to_string(kMaxImageSide) +
                        " pixels on a side; downscale it first");
    }
  }
  if (spec.depth > 1) {
    return make_error("cannot read image " + path + ": it is a volume (depth " +
                      std::to_string(spec.depth) + "); only 2D images are supported");
  }
  if (spec.nchannels < 1 || spec.nchannels > kMaxChannels) {
    return make_error("cannot read image " + path + ": it has " + std::to_string(spec.nchannels) +
                      " channels; 1 to " + std::to_string(kMaxChannels) + " are supported");
  }
  const std::string ext = lowercase_extension(path);
  const uint64_t file_bytes = files::regular_file_size(path);
  if (ext == "tif" || ext == "tiff") {
    const int bits =
        spec.get_int_attribute("oiio:BitsPerSample", static_cast<int>(spec.format.size()) * 8);
    if (auto ok = check_tiff_length(path, spec.get_string_attribute("compression"), file_bytes,
                                    spec.width, spec.height, spec.nchannels, bits);
        !ok) {
      return ok;
    }
  }
  if (auto ok =
          check_declared_size(path, ext, file_bytes, spec.width, spec.height, spec.nchannels,
                              shown.width, shown.height, static_cast<int>(spec.format.size()));
      !ok) {
    return ok;
  }
  return check_tiff_strips(path);
}

}  // namespace

Result<std::string> file_colorspace(const std::string& path, const ColorConfig& config) {
  auto input = open_input(path, nullptr);
  if (!input) return input.error();
  return colorspace_from_spec((*input)->spec(), config);
}

namespace {

// CMYK(+alpha) TIFFs: OIIO converts plain 4-channel CMYK to RGB itself but hands over
// CMYK+alpha as raw inks ("ink0".."ink4"); those are converted here, never shown as RGB.
bool has_raw_inks(const OIIO::ImageSpec& spec) {
  const bool separated = spec.get_int_attribute("tiff:PhotometricInterpretation", -1) == 5 ||
                         spec.get_string_attribute("oiio:ColorSpace") == "color separated";
  return separated && spec.nchannels >= 4 && spec.channelindex("R") < 0;
}

void inks_to_rgb(const float* src, int n, float* dst) {
  const float k = 1.0f - src[3];
  dst[0] = (1.0f - src[0]) * k;
  dst[1] = (1.0f - src[1]) * k;
  dst[2] = (1.0f - src[2]) * k;
  dst[3] = n >= 5 ? src[4] : 1.0f;
}

// NaN and Inf never leave the reader (a blur would spread one NaN over the whole picture):
// NaN -> 0, +-Inf -> +-65504 (the largest half, so it stays finite in half textures too).
size_t replace_non_finite(std::vector<float>& values) {
  size_t replaced = 0;
  for (float& v : values) {
    if (std::isfinite(v)) continue;
    v = std::isnan(v) ? 0.0f : std::copysign(65504.0f, v);
    ++replaced;
  }
  return replaced;
}

}  // namespace

namespace {
Result<ImageF> read_image_within_budget(const std::string& path, const ColorConfig& config,
                                        const std::string& colorspace_override,
                                        ImageReadNotes* notes);
}  // namespace

Result<ImageF> read_image(const std::string& path, const ColorConfig& config,
                          const std::string& colorspace_override, ImageReadNotes* notes) {
  // The budget is checked before decoding; what the machine refuses below it (a ulimit, other
  // processes) is still an error naming the file, never an uncaught exception.
  try {
    return read_image_within_budget(path, config, colorspace_override, notes);
  } catch (const std::bad_alloc&) {
    return make_error("cannot read image " + path +
                      ": out of memory while decoding it (lower AQUARELLE_MEMORY_BUDGET_MB so "
                      "such files are refused, or free memory)");
  }
}

namespace {

Result<ImageF> read_image_within_budget(const std::string& path, const ColorConfig& config,
                                        const std::string& colorspace_override,
                                        ImageReadNotes* notes) {
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

  // The data window, top row first as stored.
  const int w = spec.width, h = spec.height, n = spec.nchannels;
  std::vector<float> file_pixels(static_cast<size_t>(w) * n * h);
  {
    SilencedStderr quiet(lowercase_extension(path) == "png");
    if (!input->read_image(0, 0, 0, n, OIIO::TypeDesc::FLOAT, file_pixels.data())) {
      std::string reason = trim(input->geterror());
      if (reason.empty()) reason = trim(oiio_error());
      return make_error("cannot read the pixels of image " + path + ": " + reason +
                        " (the file is probably truncated or corrupt; re-export it)");
    }
  }
  // OIIO records a strip it could not decode (a truncated PackBits or LZW TIFF) and still
  // returns true, with black where the strip was: that is an error, never a picture.
  if (std::string late = trim(input->geterror()); !late.empty() && late != "no details") {
    return make_error("cannot read the pixels of image " + path + ": " + late +
                      " (the file is truncated or corrupt: its missing pixels would read as "
                      "black; re-export it)");
  }
  const bool straight_alpha = spec.get_int_attribute("oiio:UnassociatedAlpha", 0) != 0;
  input->close();
  const size_t non_finite = replace_non_finite(file_pixels);
  if (notes != nullptr) notes->non_finite_values = non_finite;

  // The display window is the picture; data outside it is dropped and display pixels the data
  // window does not cover are transparent black (OpenEXR's convention). Row 0 of the result
  // is the bottom of the picture, as GL expects.
  const Window shown = display_window(spec);
  const bool inks = has_raw_inks(spec);
  const ChannelMap map = map_channels(spec);
  const bool has_alpha = inks ? n >= 5 : map.alpha >= 0;
  ImageF image(shown.width, shown.height, 4);
  for (int row = 0; row < h; ++row) {
    const int y_top = spec.y + row - shown.y;
    if (y_top < 0 || y_top >= shown.height) continue;
    const int y = shown.height - 1 - y_top;
    for (int col = 0; col < w; ++col) {
      const int x = spec.x + col - shown.x;
      if (x < 0 || x >= shown.width) continue;
      const float* src = file_pixels.data() + (static_cast<size_t>(row) * w + col) * n;
      float* dst = &image.at(x, y, 0);
      if (inks) {
        inks_to_rgb(src, n, dst);
        continue;
      }
      dst[0] = src[map.red];
      dst[1] = src[map.green];
      dst[2] = src[map.blue];
      dst[3] = map.alpha >= 0 ? src[map.alpha] : 1.0f;
    }
  }
  file_pixels = {};

  if (auto ok = config.to_working(image, colorspace); !ok) {
    return make_error("cannot read image " + path + ": " + ok.message());
  }
  const size_t count = static_cast<size_t>(shown.width) * shown.height;
  if (straight_alpha && has_alpha) {
    for (size_t i = 0; i < count; ++i) {
      float* px = image.pixels.data() + i * 4;
      px[0] *= px[3];
      px[1] *= px[3];
      px[2] *= px[3];
    }
  }
  // A colour transform of huge values can overflow again.
  replace_non_finite(image.pixels);
  return image;
}

}  // namespace

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

// The temporary being written, for remove_temporary_in_progress (a signal handler): a fixed
// buffer, since a handler may not allocate.
char g_temporary_in_progress[4096] = {};

class TemporaryInProgress {
 public:
  explicit TemporaryInProgress(const std::string& path) {
    if (path.size() < sizeof(g_temporary_in_progress)) {
      std::memcpy(g_temporary_in_progress, path.c_str(), path.size() + 1);
    }
  }
  ~TemporaryInProgress() { g_temporary_in_progress[0] = '\0'; }
  TemporaryInProgress(const TemporaryInProgress&) = delete;
  TemporaryInProgress& operator=(const TemporaryInProgress&) = delete;
};

Status write_atomically(const std::string& path, const std::vector<unsigned char>& bytes) {
  const std::string temp = temporary_write_path(path, ::getpid());
  TemporaryInProgress in_progress(temp);
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

// Encodes `image` (row 0 at the bottom, float pixels) into the bytes of the file format `path`
// names, in memory, so that writers can put them in place atomically. `create_hint` follows
// the message when the format has no writer.
Result<std::vector<unsigned char>> encode_image(const std::string& path, const ImageF& image,
                                                const OIIO::ImageSpec& spec,
                                                const std::string& create_hint) {
  std::vector<unsigned char> bytes;
  OIIO::Filesystem::IOVecOutput memory(bytes);
  auto output = OIIO::ImageOutput::create(path, &memory);
  if (!output)
    return make_error("cannot write image " + path + ": " + trim(oiio_error()) + create_hint);
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
  return bytes;
}

}  // namespace

void remove_temporary_in_progress() {
  if (g_temporary_in_progress[0] != '\0') ::unlink(g_temporary_in_progress);
}

std::string temporary_write_path(const std::string& path, long pid) {
  const std::filesystem::path target(path);
  const std::string name = "." + target.filename().string() + kTemporaryMark + std::to_string(pid);
  return (target.parent_path() / name).string();
}

int remove_stale_temporaries(const std::string& path) {
  const std::filesystem::path target(path);
  const std::string prefix = "." + target.filename().string() + kTemporaryMark;
  std::filesystem::path dir = target.parent_path();
  if (dir.empty()) dir = ".";
  std::error_code ec;
  int removed = 0;
  for (const auto& entry : std::filesystem::directory_iterator(dir, ec)) {
    const std::string name = entry.path().filename().string();
    if (name.rfind(prefix, 0) != 0) continue;
    const std::string digits = name.substr(prefix.size());
    if (digits.empty() || digits.size() > 9 ||
        digits.find_first_not_of("0123456789") != std::string::npos) {
      continue;
    }
    // A writer that is still running keeps its temporary; one that died left it behind.
    const long pid = std::stol(digits);
    if (pid != ::getpid() && ::kill(static_cast<pid_t>(pid), 0) == 0) continue;
    if (std::filesystem::remove(entry.path(), ec)) ++removed;
  }
  return removed;
}

bool is_complete_image(const std::string& path) {
  OIIO::ImageSpec hints;
  auto input = open_input(path, &hints);
  if (!input) return false;
  const OIIO::ImageSpec spec = (*input)->spec();
  if (!check_spec(path, spec)) return false;
  std::vector<float> pixels(static_cast<size_t>(spec.width) * spec.height * spec.nchannels);
  SilencedStderr quiet(lowercase_extension(path) == "png");
  const bool read =
      (*input)->read_image(0, 0, 0, spec.nchannels, OIIO::TypeDesc::FLOAT, pixels.data());
  (void)OIIO::geterror();
  return read;
}

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

  auto bytes = encode_image(path, image, spec, " (use .exr, .hdr, .png, .jpg or .tif)");
  if (!bytes.ok()) return bytes.error();

  if (!ec && std::filesystem::exists(target_status) &&
      !std::filesystem::is_regular_file(target_status)) {
    return write_to_special_file(path, *bytes);
  }
  return write_atomically(path, *bytes);
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
  auto bytes = encode_image(path, image, spec, "");
  if (!bytes.ok()) return bytes.error();
  return write_atomically(path, *bytes);
}

}  // namespace aq
