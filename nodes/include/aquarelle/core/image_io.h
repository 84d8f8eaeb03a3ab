// Reading and writing image files through OpenImageIO. Reading gives RGBA float pixels in the
// working space with row 0 at the bottom (GL convention); writing keeps EXR/HDR linear and
// quantises PNG/JPEG/TIFF pixels that are already display-referred. Writes are atomic.
#pragma once

#include <aquarelle/core/color.h>
#include <aquarelle/core/image.h>
#include <aquarelle/core/result.h>

#include <cstddef>
#include <string>

namespace aq {

// Larger images are refused before any pixel memory is allocated.
inline constexpr int kMaxImageSide = 16384;

// Reads any format OIIO reads into 4-channel float (grey -> rgb, missing alpha = 1), flipped
// so row 0 is the bottom row, converted to the working space from the file's colour space:
// `colorspace_override` when given; else OIIO's "oiio:ColorSpace" metadata when it names a
// space of the config (or "sRGB"/"Linear"); else linear for float/half files (EXR, HDR) and
// sRGB for integer files (PNG, JPEG, TIFF...). Alpha comes back associated (premultiplied) in
// the working space: straight-alpha files (PNG...) are linearised first, then premultiplied.
// Errors name the path and say how to fix.
// Only regular files are read; declared sizes are checked against the file's size and the
// memory budget (AQUARELLE_MEMORY_BUDGET_MB) before pixels are allocated. The result has the
// size of the display window (EXR data windows are placed in it). NaN and Inf are replaced
// (NaN -> 0, Inf -> +-65504) and counted in `notes`, so the caller can warn. CMYK(+alpha)
// TIFFs come back as RGB(A).
struct ImageReadNotes {
  size_t non_finite_values = 0;  // NaN/Inf values in the file, replaced
};
Result<ImageF> read_image(const std::string& path, const ColorConfig& config,
                          const std::string& colorspace_override = "",
                          ImageReadNotes* notes = nullptr);

// The colour space read_image would assume for `path` without an override (opens the header).
Result<std::string> file_colorspace(const std::string& path, const ColorConfig& config);

struct WriteOptions {
  bool float_data = false;  // EXR: 32-bit float instead of half
  int bits = 8;             // PNG/TIFF: 8 or 16 (JPEG is always 8)
};

// Writes `image` (row 0 at the bottom; 1, 3 or 4 channels). EXR/HDR keep linear data as given
// (associated alpha); PNG/JPEG/TIFF expect display-referred pixels with straight alpha (the
// output of DisplayTransform), which are clamped to [0,1], quantised and stored unchanged
// (JPEG and HDR drop alpha). Atomic: the pixels go to DIR/.NAME.tmp-<pid> first (hidden, so
// it matches no NAME*.exr glob) and are renamed over PATH; on any failure (disk full,
// unwritable directory) nothing is left behind and the error names the path and the reason.
Status write_image(const std::string& path, const ImageF& image, const WriteOptions& options = {});

// The temporary write_image uses for `path` in process `pid`.
std::string temporary_write_path(const std::string& path, long pid);

// Removes the temporary a write_image in progress is writing, if any. Async-signal-safe: for a
// handler that ends the process in the middle of a write.
void remove_temporary_in_progress();

// Removes temporaries of `path` left by writers that died (SIGKILL, power loss); a running
// writer's is kept. Returns how many were removed.
int remove_stale_temporaries(const std::string& path);

// Whether `path` is a regular image file whose pixels all read (false when truncated).
bool is_complete_image(const std::string& path);

// png, jpg, jpeg, tif, tiff -> true; exr, hdr and anything else -> false (case-insensitive).
bool is_display_referred_format(const std::string& path);

}  // namespace aq

namespace aq {

// Writes an EXR whose channels carry the given names, e.g. "R", "G", "B", "A", "normal.X",
// "normal.Y", "normal.Z", "depth.Z" (Nuke reads "layer.channel" as layers). `image` has one
// channel per name, row 0 at the bottom; half unless options.float_data. Atomic.
Status write_exr_channels(const std::string& path, const ImageF& image,
                          const std::vector<std::string>& channel_names,
                          const WriteOptions& options = {});

}  // namespace aq
