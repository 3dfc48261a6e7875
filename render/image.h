// 8-bit RGBA images and PNG input/output.
//
// PNG encoding uses libpng with zlib level 2 and the fixed "sub" filter (measured: ~5 ms for
// 640x480 and ~15 ms for 1280x720, against ~50/150 ms for stb_image_write's defaults); decoding
// uses stb_image. Pixels are compared and hashed on the decoded RGBA, never on PNG bytes.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace render {

// A width x height image, rows top-down, 4 bytes per pixel (R, G, B, A; sRGB, straight alpha).
// Pixel (x, y) starts at rgba[4 * (y * width + x)].
struct Image {
  int width = 0;
  int height = 0;
  std::vector<std::uint8_t> rgba;

  Image() = default;
  // A width x height image filled with one colour.
  Image(int w, int h, std::uint8_t r = 0, std::uint8_t g = 0, std::uint8_t b = 0,
        std::uint8_t a = 255);
  bool empty() const { return width == 0 || height == 0; }
  std::uint8_t* at(int x, int y) { return &rgba[4 * (static_cast<size_t>(y) * width + x)]; }
  const std::uint8_t* at(int x, int y) const {
    return &rgba[4 * (static_cast<size_t>(y) * width + x)];
  }
};

// True when both images have the same size and identical bytes.
bool SameImage(const Image& a, const Image& b);

// Encodes `image` as an 8-bit RGBA PNG in memory. `zlib_level` 0..9 (default 2: fast, files
// ~25% larger than level 6). Byte-identical output for identical input.
std::string EncodePng(const Image& image, int zlib_level = 2);

// Writes `image` to `path` as PNG, atomically (a temporary file in the same folder, then rename).
// Creates missing parent folders. Throws std::runtime_error naming the path on failure.
void WritePng(const std::string& path, const Image& image, int zlib_level = 2);


// Limits of PNG input, checked before decoding: file bytes and pixels (width × height, read from
// the header; 8192 × 8192 = 256 MB of RGBA).
inline constexpr std::size_t kMaxPngFileBytes = std::size_t{64} << 20;
inline constexpr long long kMaxImagePixels = 8192LL * 8192LL;

// Decodes a PNG file into RGBA (grey, grey+alpha and RGB inputs are expanded; 16-bit is reduced
// to 8-bit). Throws std::invalid_argument naming the path when the file is missing, is not a PNG
// (checked by signature), is larger than kMaxPngFileBytes (reading stops there: `/dev/zero` is
// refused), has more than kMaxImagePixels pixels, or cannot be decoded.
Image ReadPng(const std::string& path);
// The same for a PNG held in memory; `source_name` is used in error messages.
Image DecodePng(const std::string& bytes, const std::string& source_name);

// Nearest-neighbour-free box-filter downscale to (w, h) (each output pixel averages the input
// pixels it covers). Used for thumbnails and contact sheets.
Image Downscale(const Image& image, int w, int h);

// FNV-1a 64-bit hash of the pixel bytes (and size), for logs and determinism checks.
std::uint64_t HashImage(const Image& image);

}  // namespace render
