#include "image_limits.h"

#include <aquarelle/core/image_io.h>
#include <aquarelle/sdk/regular_file.hpp>

#include <sys/stat.h>
#include <unistd.h>
#include <zlib.h>

#include <algorithm>
#include <cctype>
#include <cstdint>
#include <cstring>
#include <memory>
#include <string>
#include <vector>

namespace aq {
namespace {

// zlib's deflate reaches at most 1032:1 (258-byte matches coded in 2 bits); a little slack
// covers headers and rounding.
constexpr uint64_t kDeflateMaxRatio = 1100;

std::string megabytes(uint64_t bytes) {
  return std::to_string((bytes + (1u << 20) - 1) >> 20) + " MiB";
}

// The unsigned integer of the `n` bytes at `p`, big-endian unless `little`.
uint64_t unsigned_at(const unsigned char* p, int n, bool little = false) {
  uint64_t v = 0;
  for (int i = 0; i < n; ++i) v = (v << 8) | p[little ? n - 1 - i : i];
  return v;
}

// A header is read through its own descriptor, closed on every return path.
class HeaderFile {
 public:
  explicit HeaderFile(int fd) : fd_(fd) {
    struct stat info {};
    if (fd_ >= 0 && ::fstat(fd_, &info) == 0) size_ = static_cast<uint64_t>(info.st_size);
  }
  HeaderFile(const HeaderFile&) = delete;
  HeaderFile& operator=(const HeaderFile&) = delete;
  ~HeaderFile() {
    if (fd_ >= 0) ::close(fd_);
  }
  bool read(void* out, size_t n, uint64_t at) const {
    return ::pread(fd_, out, n, static_cast<off_t>(at)) == static_cast<ssize_t>(n);
  }
  uint64_t size() const { return size_; }

 private:
  int fd_ = -1;
  uint64_t size_ = 0;
};

Result<std::unique_ptr<HeaderFile>> open_header(const std::string& path) {
  std::string why;
  const int fd = files::open_regular_file(path, &why);
  if (fd < 0) return make_error("cannot read image " + path + ": " + why);
  return std::make_unique<HeaderFile>(fd);
}

}  // namespace

uint64_t decoded_image_bytes(int w, int h, int n, int full_w, int full_h, int native_bytes) {
  const auto area = static_cast<uint64_t>(w) * static_cast<uint64_t>(h);
  const auto shown = static_cast<uint64_t>(full_w) * static_cast<uint64_t>(full_h);
  const auto per_value = sizeof(float) + static_cast<uint64_t>(std::max(native_bytes, 1));
  return area * static_cast<uint64_t>(n) * per_value + 2 * shown * 4 * sizeof(float);
}

Status check_tiff_length(const std::string& path, const std::string& compression,
                         uint64_t file_bytes, int w, int h, int n, int bits_per_sample) {
  if (!(compression.empty() || compression == "none")) return Ok{};
  const uint64_t row_bits = static_cast<uint64_t>(w) * static_cast<uint64_t>(n) *
                            static_cast<uint64_t>(std::max(bits_per_sample, 1));
  const uint64_t pixel_bytes = (row_bits + 7) / 8 * static_cast<uint64_t>(h);
  if (pixel_bytes > file_bytes) {
    return make_error("cannot read image " + path + ": it declares " + std::to_string(w) + "x" +
                      std::to_string(h) + " uncompressed pixels (" + std::to_string(pixel_bytes) +
                      " bytes) but the file holds only " + std::to_string(file_bytes) +
                      " bytes: it is truncated; re-export it");
  }
  return Ok{};
}

Status check_declared_size(const std::string& path, const std::string& ext, uint64_t file_bytes,
                           int w, int h, int n, int full_w, int full_h, int native_bytes) {
  if (w <= 0 || h <= 0 || n <= 0 || full_w <= 0 || full_h <= 0) {
    return make_error("cannot read image " + path + ": its header declares no pixels");
  }
  if (ext == "png") {
    // The least a PNG of this size can decompress to: one bit per pixel plus a filter byte
    // per row (1-bit greyscale or palette).
    const uint64_t least_raw = static_cast<uint64_t>(h) * (1 + (static_cast<uint64_t>(w) + 7) / 8);
    if (least_raw > file_bytes * kDeflateMaxRatio + 65536) {
      return make_error("cannot read image " + path + ": its header declares " + std::to_string(w) +
                        "x" + std::to_string(h) +
                        " pixels, which cannot "
                        "be stored in a file of " +
                        std::to_string(file_bytes) +
                        " bytes (the header is corrupt or forged; re-export the image)");
    }
  }
  const uint64_t need = decoded_image_bytes(w, h, n, full_w, full_h, native_bytes);
  const uint64_t budget = files::memory_budget_bytes();
  if (need > budget) {
    return make_error("cannot read image " + path + ": decoding its " + std::to_string(w) + "x" +
                      std::to_string(h) + " pixels of " + std::to_string(n) + " channels needs " +
                      megabytes(need) + ", more than the memory budget of " + megabytes(budget) +
                      " (downscale the image, or raise AQUARELLE_MEMORY_BUDGET_MB)");
  }
  return Ok{};
}

// OpenEXR reads these attribute types by their own structure, not by their declared size: a
// channel list runs until its empty name, a string vector and a preview allocate what they
// declare inside. Their structure must end within the declared size ("" when it does).
std::string exr_attribute_problem(const std::string& type, const std::string& value) {
  const uint64_t size = value.size();
  auto u32_at = [&](uint64_t at) {
    uint32_t v = 0;
    std::memcpy(&v, value.data() + at, 4);
    return v;
  };
  if (type == "chlist") {
    uint64_t at = 0;
    while (at < size) {
      const auto end = value.find('\0', at);
      if (end == std::string::npos) break;
      if (end == at) return {};  // the empty name ends the list
      at = end + 1 + 16;         // pixel type, pLinear + reserved, x and y sampling
    }
    return "is a channel list that does not end within its " + std::to_string(size) + " bytes";
  }
  if (type == "stringvector") {
    for (uint64_t at = 0; at < size;) {
      if (at + 4 > size) return "is a string vector cut inside a length";
      const uint64_t length = u32_at(at);
      if (length > size - at - 4) {
        return "holds a string of " + std::to_string(length) + " bytes in " + std::to_string(size) +
               " bytes";
      }
      at += 4 + length;
    }
    return {};
  }
  if (type == "preview") {
    if (size < 8) return "is a preview without its size";
    const uint64_t pixels = uint64_t{u32_at(0)} * uint64_t{u32_at(4)};
    if (pixels * 4 + 8 != size) {
      return "declares a " + std::to_string(u32_at(0)) + "x" + std::to_string(u32_at(4)) +
             " preview in " + std::to_string(size) + " bytes";
    }
  }
  return {};
}

Status check_exr_header(const std::string& path) {
  auto file = open_header(path);
  if (!file.ok()) return file.error();
  const HeaderFile& header = **file;
  const uint64_t size = header.size();
  uint64_t at = 0;
  auto read_at = [&](void* out, size_t n) {
    if (!header.read(out, n, at)) return false;
    at += n;
    return true;
  };
  unsigned char magic[8] = {};
  if (!read_at(magic, 8) || magic[0] != 0x76 || magic[1] != 0x2f || magic[2] != 0x31 ||
      magic[3] != 0x01) {
    return Ok{};  // not an EXR file
  }
  // A null-terminated name of at most 255 characters (OpenEXR's long-name limit); without the
  // long-names flag OpenEXR reads at most 31 characters and takes the next byte as the following
  // field: a longer name would desynchronise our walk from its reading.
  const size_t longest_name = (magic[5] & 0x04) != 0 ? 255 : 31;
  auto read_name = [&](std::string* name) {
    name->clear();
    char c = 0;
    while (read_at(&c, 1)) {
      if (c == '\0') return true;
      if (name->size() >= longest_name) return false;
      name->push_back(c);
    }
    return false;
  };
  auto refuse = [&](const std::string& what) {
    return make_error("cannot read image " + path + ": its OpenEXR header " + what +
                      " (the file is corrupt or forged; re-export it)");
  };
  const bool multipart = (magic[5] & 0x10) != 0;
  std::string name, type;
  for (int headers = 0; headers < 1024; ++headers) {
    int attributes = 0;
    while (true) {
      if (!read_name(&name)) {
        return refuse("ends inside an attribute name, or has one longer than " +
                      std::to_string(longest_name) + " characters");
      }
      if (name.empty()) break;  // end of this header
      if (++attributes > 4096) return refuse("has more than 4096 attributes");
      if (!read_name(&type)) return refuse("ends inside the type of attribute " + name);
      int32_t declared = 0;
      if (!read_at(&declared, 4)) return refuse("ends before the size of attribute " + name);
      if (declared < 0 || static_cast<uint64_t>(declared) > size - at) {
        return refuse("declares " + std::to_string(declared) + " bytes for attribute '" + name +
                      "' but only " + std::to_string(size - at) + " bytes follow");
      }
      if (name == "dataWindow" && type == "box2i" && declared == 16) {
        // OpenEXR sizes its line buffers by the data window when it opens the file, before
        // OIIO's size checks see it (a 613-byte file declaring 8388612 x 3 pixels made it
        // allocate gigabytes): the window is held to the sides any image may have.
        int32_t box[4] = {};
        if (!header.read(box, sizeof(box), at)) return refuse("ends inside " + name);
        const int64_t w = int64_t{box[2]} - box[0] + 1, h = int64_t{box[3]} - box[1] + 1;
        if (w < 1 || h < 1 || w > kMaxImageSide || h > kMaxImageSide) {
          return refuse("declares a " + std::to_string(w) + "x" + std::to_string(h) +
                        " data window; an image may have 1 to " + std::to_string(kMaxImageSide) +
                        " pixels a side");
        }
      }
      if (type == "chlist" || type == "stringvector" || type == "preview") {
        std::string value(static_cast<size_t>(declared), '\0');
        if (!header.read(value.data(), value.size(), at)) return refuse("ends inside " + name);
        if (std::string why = exr_attribute_problem(type, value); !why.empty()) {
          return refuse("attribute '" + name + "' " + why);
        }
      }
      at += static_cast<uint64_t>(declared);
    }
    if (!multipart || attributes == 0) break;  // single part, or the empty header ending parts
  }
  return Ok{};
}

Status check_png_chunks(const std::string& path) {
  auto file = open_header(path);
  if (!file.ok()) return file.error();
  const HeaderFile& header = **file;
  const uint64_t size = header.size();
  static constexpr unsigned char kSignature[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
  unsigned char head[8] = {};
  if (!header.read(head, 8, 0) || std::memcmp(head, kSignature, 8) != 0) {
    return Ok{};  // not a PNG file
  }
  uint64_t at = 8;
  // Each chunk: 4-byte big-endian length, 4-byte type, data, 4-byte CRC.
  for (int chunks = 0; at + 8 <= size; ++chunks) {
    unsigned char chunk[8] = {};
    if (!header.read(chunk, 8, at)) break;
    const uint64_t length = unsigned_at(chunk, 4);
    const std::string type(reinterpret_cast<const char*>(chunk + 4), 4);
    at += 8;
    const uint64_t left = size - at;
    if (length > 0x7fffffffu || length + 4 > left) {
      const bool printable =
          std::all_of(type.begin(), type.end(), [](char c) { return std::isalpha(uint8_t(c)); });
      return make_error("cannot read image " + path + ": its PNG chunk " +
                        (printable ? "'" + type + "' " : "") + "number " +
                        std::to_string(chunks + 1) + " declares " + std::to_string(length) +
                        " bytes but only " + std::to_string(left) +
                        " follow (the file is truncated, corrupt or forged; re-export it)");
    }
    at += length + 4;
    if (type == "IEND") break;
  }
  return Ok{};
}

namespace {

// Reads a file forward one byte at a time through a 64 KiB window: the JPEG walk below skips
// garbage byte by byte, as libjpeg does, and a pread per byte would take seconds on a large file.
class ForwardBytes {
 public:
  explicit ForwardBytes(const HeaderFile& file) : file_(file) {}
  // The byte at `at`, or -1 past the end.
  int at(uint64_t at) {
    if (at >= file_.size()) return -1;
    if (at < start_ || at >= start_ + filled_) {
      start_ = at;
      filled_ = static_cast<size_t>(std::min<uint64_t>(sizeof(window_), file_.size() - at));
      if (!file_.read(window_, filled_, at)) {
        filled_ = 0;
        return -1;
      }
    }
    return window_[at - start_];
  }

 private:
  const HeaderFile& file_;
  unsigned char window_[64 * 1024] = {};
  uint64_t start_ = 0;
  size_t filled_ = 0;
};

// What OpenImageIO 2.4 would read past in a Photoshop segment's data after its "Photoshop 3.0"
// signature (`data`, the signature's 14 bytes included), or "" when everything fits. It reads
// the first resource's 12-byte header unchecked once it begins "8BIM", and trusts the sizes of
// the resources and of the IPTC records in them (it read past the segment on a fuzzed file).
// 8BIM resources: signature, id, an empty name (OpenImageIO expects two zero bytes), size, data
// padded to even; the IPTC one (0x0404) holds records 0x1C, record, dataset, 2-byte length,
// data.
std::string photoshop_problem(const std::vector<unsigned char>& data) {
  const size_t rest = data.size() - 14;
  if (rest < 12 && std::memcmp(data.data() + 14, "8BIM", std::min<size_t>(rest, 4)) == 0) {
    return "ends inside the header of its first resource";
  }
  size_t p = 14;
  while (p + 12 <= data.size() && std::memcmp(data.data() + p, "8BIM", 4) == 0) {
    const uint64_t id = unsigned_at(data.data() + p + 4, 2);
    if (data[p + 6] != 0 || data[p + 7] != 0) return "names a resource";
    const uint64_t resource_bytes = unsigned_at(data.data() + p + 8, 4);
    const size_t start = p + 12;
    if (resource_bytes > data.size() - start) {
      return "declares a resource of " + std::to_string(resource_bytes) + " bytes where " +
             std::to_string(data.size() - start) + " are left";
    }
    const size_t end = start + resource_bytes;
    for (size_t r = start; id == 0x0404 && r < end && data[r] == 0x1C;) {
      if (r + 5 > end) return "ends inside a record header";
      const uint64_t record = unsigned_at(data.data() + r + 3, 2);
      if (record & 0x8000) return "uses an extended record length";
      if (record > end - (r + 5)) return "declares a record past its end";
      r += 5 + record;
    }
    p = end + (resource_bytes & 1);
  }
  return "";
}

// The next marker after `at` as libjpeg's next_marker finds it: bytes before an 0xFF are
// skipped as garbage (a segment whose length was forged short leaves some), 0xFF runs are fill,
// and "FF 00" is stuffed data, not a marker. Returns the marker's code and leaves `at` after it,
// or -1 at the end of the file.
int next_jpeg_marker(ForwardBytes& bytes, uint64_t& at) {
  while (true) {
    int c = bytes.at(at);
    while (c >= 0 && c != 0xFF) c = bytes.at(++at);
    while (c == 0xFF) c = bytes.at(++at);
    if (c < 0) return -1;
    ++at;
    if (c != 0) return c;
  }
}

}  // namespace

Status check_jpeg_metadata(const std::string& path) {
  auto file = open_header(path);
  if (!file.ok()) return file.error();
  const HeaderFile& header = **file;
  const uint64_t size = header.size();
  unsigned char soi[2] = {};
  if (!header.read(soi, 2, 0) || soi[0] != 0xFF || soi[1] != 0xD8) return Ok{};  // not a JPEG
  auto refuse = [&](const char* segment, const std::string& what) -> Status {
    return make_error("cannot read image " + path + ": its " + segment + " " + what +
                      " (the file is corrupt or forged; re-export it, or strip its metadata)");
  };
  ForwardBytes bytes(header);
  uint64_t at = 2;
  while (true) {
    const int code = next_jpeg_marker(bytes, at);
    if (code < 0 || code == 0xD9 || code == 0xDA) break;  // no more metadata before the scan
    if (code == 0x01 || (code >= 0xD0 && code <= 0xD7)) continue;  // markers without a length
    unsigned char length_bytes[2] = {};
    if (!header.read(length_bytes, 2, at)) break;
    const uint64_t length = unsigned_at(length_bytes, 2);
    if (length < 2 || at + length > size) break;  // libjpeg reports a truncated file
    const bool exif = code == 0xE1, photoshop = code == 0xED;
    const char* segment = exif ? "Exif metadata (APP1)" : "Photoshop/IPTC metadata (APP13)";
    const size_t held = static_cast<size_t>(length - 2);
    // OpenImageIO 2.4 finds Exif and Photoshop metadata with strcmp, which reads on past a
    // segment that ends inside the signature, and then decodes Exif from 6 bytes in, over
    // data_length - 6 bytes: an unsigned count that wraps to 4 GiB below 6.
    if ((exif && held < 6) || (photoshop && held < 14)) {
      const char* signature = exif ? "Exif\0" : "Photoshop 3.0";  // with its final zero byte
      char head[14] = {};
      if (held > 0 && header.read(head, held, at + 2) && std::memcmp(head, signature, held) == 0) {
        return refuse(segment, "ends inside its header");
      }
    } else if (photoshop) {
      std::vector<unsigned char> data(held);
      if (!header.read(data.data(), data.size(), at + 2)) break;
      if (std::memcmp(data.data(), "Photoshop 3.0", 14) == 0) {
        if (std::string why = photoshop_problem(data); !why.empty()) return refuse(segment, why);
      }
    }
    at += length;
  }
  return Ok{};
}

namespace {

// The tags of a classic TIFF's first directory that say where its pixels are.
struct TiffLayout {
  uint64_t width = 0, height = 0, bits = 1, samples = 1, compression = 1, planar = 1;
  uint64_t photometric = 1, rows_per_strip = UINT32_MAX, tile_width = 0, tile_height = 0;
  std::vector<uint64_t> offsets, byte_counts;
};

// Reads the first directory; false when the file is not a classic TIFF this walk understands.
bool read_tiff_layout(const HeaderFile& file, TiffLayout* layout) {
  unsigned char head[8] = {};
  if (!file.read(head, 8, 0)) return false;
  const bool little = head[0] == 'I' && head[1] == 'I';
  if (!little && !(head[0] == 'M' && head[1] == 'M')) return false;
  auto number = [little](const unsigned char* p, int n) { return unsigned_at(p, n, little); };
  if (number(head + 2, 2) != 42) return false;  // BigTIFF (43) and others: OIIO's own checks
  const uint64_t directory = number(head + 4, 4);
  unsigned char count_bytes[2] = {};
  if (!file.read(count_bytes, 2, directory)) return false;
  const uint64_t entries = number(count_bytes, 2);
  for (uint64_t e = 0; e < entries; ++e) {
    unsigned char entry[12] = {};
    if (!file.read(entry, 12, directory + 2 + 12 * e)) return false;
    const uint64_t tag = number(entry, 2), type = number(entry + 2, 2);
    const uint64_t count = number(entry + 4, 4);
    const int size = type == 3 ? 2 : type == 4 ? 4 : 0;  // SHORT or LONG; others not needed
    if (size == 0) continue;
    // Each value lies inside the file: a count past it cannot be right.
    if (count == 0 || count > file.size() / static_cast<uint64_t>(size)) return false;
    std::vector<unsigned char> raw(static_cast<size_t>(count) * size);
    const uint64_t at = raw.size() <= 4 ? directory + 2 + 12 * e + 8 : number(entry + 8, 4);
    if (!file.read(raw.data(), raw.size(), at)) return false;
    std::vector<uint64_t> values(static_cast<size_t>(count));
    for (size_t i = 0; i < values.size(); ++i) values[i] = number(raw.data() + i * size, size);
    switch (tag) {
      case 256:
        layout->width = values[0];
        break;
      case 257:
        layout->height = values[0];
        break;
      case 258:
        layout->bits = values[0];
        break;
      case 259:
        layout->compression = values[0];
        break;
      case 273:
      case 324:
        layout->offsets = std::move(values);
        break;
      case 262:
        layout->photometric = values[0];
        break;
      case 277:
        layout->samples = values[0];
        break;
      case 278:
        layout->rows_per_strip = values[0];
        break;
      case 279:
      case 325:
        layout->byte_counts = std::move(values);
        break;
      case 284:
        layout->planar = values[0];
        break;
      case 322:
        layout->tile_width = values[0];
        break;
      case 323:
        layout->tile_height = values[0];
        break;
      default:
        break;
    }
  }
  return layout->width > 0 && layout->height > 0 && layout->samples > 0 && layout->bits > 0;
}

// Bytes `data` inflates to, counting no further than `enough` (zlib or raw deflate stream).
uint64_t inflated_bytes(const std::vector<unsigned char>& data, uint64_t enough) {
  z_stream stream{};
  if (inflateInit(&stream) != Z_OK) return 0;
  stream.next_in = const_cast<unsigned char*>(data.data());
  stream.avail_in = static_cast<uInt>(data.size());
  std::vector<unsigned char> out(64 << 10);
  uint64_t produced = 0;
  int status = Z_OK;
  while (status == Z_OK && produced < enough) {
    stream.next_out = out.data();
    stream.avail_out = static_cast<uInt>(out.size());
    status = inflate(&stream, Z_NO_FLUSH);
    produced += out.size() - stream.avail_out;
    if (status == Z_OK && stream.avail_in == 0 && stream.avail_out != 0) break;  // input ended
  }
  inflateEnd(&stream);
  return produced;
}

}  // namespace

Status check_tiff_strips(const std::string& path) {
  auto opened = open_header(path);
  if (!opened.ok()) return opened.error();
  const HeaderFile& file = **opened;
  TiffLayout t;
  if (!read_tiff_layout(file, &t)) return Ok{};
  auto refuse = [&](const std::string& what) -> Status {
    return make_error("cannot read image " + path + ": " + what +
                      " (the file is truncated or corrupt: its missing pixels would read as "
                      "black; re-export it)");
  };
  const bool tiled = t.tile_width > 0 && t.tile_height > 0;
  const uint64_t planes = t.planar == 2 ? t.samples : 1;
  const uint64_t per_pixel = t.bits * (t.planar == 2 ? 1 : t.samples);
  const uint64_t chunk_width = tiled ? t.tile_width : t.width;
  const uint64_t chunk_rows = tiled ? t.tile_height : std::min(t.rows_per_strip, t.height);
  if (chunk_rows == 0) return refuse("it declares strips of 0 rows");
  const uint64_t across = tiled ? (t.width + t.tile_width - 1) / t.tile_width : 1;
  const uint64_t down = (t.height + chunk_rows - 1) / chunk_rows;
  const uint64_t needed = across * down * planes;
  const char* kind = tiled ? "tiles" : "strips";
  if (t.offsets.size() < needed || t.byte_counts.size() < t.offsets.size()) {
    return refuse("its " + std::to_string(t.width) + "x" + std::to_string(t.height) +
                  " pixels need " + std::to_string(needed) + " " + kind + " but it lists " +
                  std::to_string(std::min(t.offsets.size(), t.byte_counts.size())));
  }
  // Subsampled YCbCr rows are shorter than samples x width: only the listing is checked.
  const bool deflated = (t.compression == 8 || t.compression == 32946) && t.photometric != 6;
  const uint64_t row_bytes = (chunk_width * per_pixel + 7) / 8;
  for (uint64_t i = 0; i < needed; ++i) {
    const uint64_t at = t.offsets[i], bytes = t.byte_counts[i];
    if (at > file.size() || bytes > file.size() - at) {
      return refuse("its " + std::string(kind, tiled ? 4 : 5) + " " + std::to_string(i) +
                    " lies past the end of the file");
    }
    if (!deflated) continue;
    // A strip holds its rows; the last strip of a plane only those left.
    const uint64_t row = (i % (across * down)) / across * chunk_rows;
    const uint64_t rows = tiled ? chunk_rows : std::min(chunk_rows, t.height - row);
    const uint64_t expected = rows * row_bytes;
    std::vector<unsigned char> data(static_cast<size_t>(bytes));
    if (!file.read(data.data(), data.size(), at)) return refuse("it cannot be read whole");
    if (const uint64_t got = inflated_bytes(data, expected); got < expected) {
      return refuse("its " + std::string(kind, tiled ? 4 : 5) + " " + std::to_string(i) +
                    " inflates to " + std::to_string(got) + " of its " + std::to_string(expected) +
                    " bytes");
    }
  }
  return Ok{};
}

}  // namespace aq
