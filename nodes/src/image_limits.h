// What an image header may declare before any pixel memory is allocated: a tiny file cannot
// hold a huge picture (deflate compresses at most ~1032:1, so a PNG's declared size bounds
// its file size from below), and the decoded pixels must fit the memory budget
// (files::memory_budget_bytes, AQUARELLE_MEMORY_BUDGET_MB). Pure: the fuzzer and the tests
// call it on made-up headers.
#pragma once

#include <aquarelle/core/result.h>

#include <cstdint>
#include <string>

namespace aq {

// Bytes that decoding a w x h image of n channels (data window) shown in a full_w x full_h
// display window allocates while reading and using it: the reader's native buffer
// (`native_bytes` per channel value: 1 for 8-bit, 2 for half or 16-bit, 4 for float; OIIO's
// PNG and TIFF readers hold the whole image), the float pixels converted from it, the RGBA
// float result and its texture (up to RGBA float again; on llvmpipe textures live in host
// memory).
uint64_t decoded_image_bytes(int w, int h, int n, int full_w, int full_h, int native_bytes = 4);

// Refuses a header whose declared size does not fit `file_bytes` (by the format's best
// compression ratio, where one is known) or the memory budget. `ext` is lower case.
Status check_declared_size(const std::string& path, const std::string& ext, uint64_t file_bytes,
                           int w, int h, int n, int full_w, int full_h, int native_bytes = 4);

// An uncompressed TIFF holds every pixel: a file shorter than its declared pixels is truncated
// (OIIO filled the missing strips with black, silently). `compression` as OIIO names it.
Status check_tiff_length(const std::string& path, const std::string& compression,
                         uint64_t file_bytes, int w, int h, int n, int bits_per_sample);

// OpenImageIO 2.4 fills the pixels of a TIFF strip or tile that is missing, cut short or
// decompresses to less than its rows with black and reports success (deflate) or only a
// late error (other codecs). Walks the first image's strips or tiles (classic TIFF, found by
// its byte-order mark, whatever its extension): every one the size needs must be listed and
// lie inside the file, and a deflated one must inflate to its rows. Other files pass.
Status check_tiff_strips(const std::string& path);

// OpenEXR reads header attributes by their declared size before OIIO sees the file (a 28-byte
// file declaring a 1.8 GB attribute made it allocate 1.8 GB): walks the attributes of an EXR
// file (found by its magic number, whatever its extension) and refuses sizes larger than the
// rest of the file. Other files pass.
Status check_exr_header(const std::string& path);

// libpng allocates a chunk's declared length before reading it (a 320-byte PNG declaring a
// 1.9 GB text chunk made the reader pass 1 GB): walks the chunks of a PNG file (found by its
// signature, whatever its extension) and refuses a length larger than the rest of the file or
// beyond the PNG limit of 2^31 - 1. Other files pass.
Status check_png_chunks(const std::string& path);

// OpenImageIO 2.4 trusts the sizes inside a JPEG's metadata and read past it on fuzzed files:
// walks the markers of a JPEG file (found by its SOI marker) as libjpeg finds them, garbage
// between segments skipped, and refuses Photoshop/IPTC segments (APP13) whose 8BIM resources or
// IPTC records are larger than what holds them, and an Exif (APP1) or Photoshop (APP13) segment
// that ends inside its signature or header. Other files pass.
Status check_jpeg_metadata(const std::string& path);

}  // namespace aq
