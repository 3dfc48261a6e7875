// Images and PNG input/output: libpng (fast settings) for writing, stb_image for reading.
#include "render/image.h"

#include <png.h>
#include <stb_image.h>
#include <unistd.h>

#include <algorithm>
#include <csetjmp>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include "base/file_read.h"
#include "base/file_write.h"

namespace render {
namespace {

void AppendPngBytes(png_structp png, png_bytep data, png_size_t length) {
  auto* out = static_cast<std::string*>(png_get_io_ptr(png));
  out->append(reinterpret_cast<const char*>(data), length);
}

void NoFlush(png_structp) {}

}  // namespace

Image::Image(int w, int h, std::uint8_t r, std::uint8_t g, std::uint8_t b, std::uint8_t a)
    : width(w), height(h), rgba(4 * static_cast<size_t>(std::max(w, 0)) * std::max(h, 0)) {
  for (size_t i = 0; i < rgba.size(); i += 4) {
    rgba[i] = r;
    rgba[i + 1] = g;
    rgba[i + 2] = b;
    rgba[i + 3] = a;
  }
}

bool SameImage(const Image& a, const Image& b) {
  return a.width == b.width && a.height == b.height && a.rgba == b.rgba;
}

std::string EncodePng(const Image& image, int zlib_level) {
  if (image.empty() || image.rgba.size() != 4 * static_cast<size_t>(image.width) * image.height) {
    throw std::invalid_argument("EncodePng: empty image or pixel buffer of the wrong size");
  }
  std::string out;
  std::vector<png_bytep> rows(static_cast<size_t>(image.height));
  for (int y = 0; y < image.height; ++y) {
    rows[static_cast<size_t>(y)] = const_cast<png_bytep>(image.at(0, y));
  }
  png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, nullptr, nullptr, nullptr);
  png_infop info = png ? png_create_info_struct(png) : nullptr;
  if (png == nullptr || info == nullptr) {
    png_destroy_write_struct(&png, &info);
    throw std::runtime_error("EncodePng: libpng initialisation failed");
  }
  if (setjmp(png_jmpbuf(png))) {
    png_destroy_write_struct(&png, &info);
    throw std::runtime_error("EncodePng: libpng error");
  }
  png_set_write_fn(png, &out, AppendPngBytes, NoFlush);
  png_set_compression_level(png, std::clamp(zlib_level, 0, 9));
  // One fixed filter: "sub" is cheap and good for rendered images (measured, see image.h).
  png_set_filter(png, PNG_FILTER_TYPE_BASE, PNG_FILTER_SUB);
  png_set_IHDR(png, info, static_cast<png_uint_32>(image.width),
               static_cast<png_uint_32>(image.height), 8, PNG_COLOR_TYPE_RGB_ALPHA,
               PNG_INTERLACE_NONE, PNG_COMPRESSION_TYPE_BASE, PNG_FILTER_TYPE_BASE);
  png_write_info(png, info);
  png_write_image(png, rows.data());
  png_write_end(png, nullptr);
  png_destroy_write_struct(&png, &info);
  return out;
}

void WritePng(const std::string& path, const Image& image, int zlib_level) {
  base::WriteFileAtomic(path, EncodePng(image, zlib_level));
}

Image DecodePng(const std::string& bytes, const std::string& source_name) {
  static const unsigned char kSignature[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
  if (bytes.size() < 8 || std::memcmp(bytes.data(), kSignature, 8) != 0) {
    throw std::invalid_argument(source_name + ": not a PNG file");
  }
  int w = 0, h = 0, channels = 0;
  if (bytes.size() > kMaxPngFileBytes) {
    throw std::invalid_argument(source_name + ": PNG larger than " +
                                std::to_string(kMaxPngFileBytes) + " bytes (limit)");
  }
  // The size from the header first: a small file can announce gigabytes of pixels.
  if (stbi_info_from_memory(reinterpret_cast<const unsigned char*>(bytes.data()),
                            static_cast<int>(bytes.size()), &w, &h, &channels) &&
      static_cast<long long>(w) * h > kMaxImagePixels) {
    throw std::invalid_argument(source_name + ": PNG of " + std::to_string(w) + "x" +
                                std::to_string(h) + " pixels is larger than the limit of " +
                                std::to_string(kMaxImagePixels) + " pixels");
  }
  unsigned char* pixels =
      stbi_load_from_memory(reinterpret_cast<const unsigned char*>(bytes.data()),
                            static_cast<int>(bytes.size()), &w, &h, &channels, 4);
  if (pixels == nullptr) {
    throw std::invalid_argument(source_name + ": cannot decode PNG (" + stbi_failure_reason() +
                                ")");
  }
  Image image;
  image.width = w;
  image.height = h;
  image.rgba.assign(pixels, pixels + 4 * static_cast<size_t>(w) * h);
  stbi_image_free(pixels);
  return image;
}

Image ReadPng(const std::string& path) {
  // Bounded: DecodePng refuses more than kMaxPngFileBytes.
  base::FileBytes file = base::ReadFileLimited(path, kMaxPngFileBytes);
  if (file.status == base::ReadStatus::kTooLarge) {
    throw std::invalid_argument(path + ": PNG larger than " + std::to_string(kMaxPngFileBytes) +
                                " bytes (limit)");
  }
  if (file.status != base::ReadStatus::kOk) {
    throw std::invalid_argument(path + ": cannot open (missing file?)");
  }
  return DecodePng(file.bytes, path);
}

Image Downscale(const Image& image, int w, int h) {
  if (w < 1 || h < 1 || image.empty()) throw std::invalid_argument("Downscale: empty size");
  Image out(w, h);
  if (image.width == 2 * w && image.height == 2 * h) {
    // Exactly half the size (frames' thumbnails): the 2 x 2 boxes the general loop below takes,
    // with the same rounding, without its per-pixel box bounds.
    for (int y = 0; y < h; ++y) {
      const std::uint8_t* r0 = image.at(0, 2 * y);
      const std::uint8_t* r1 = image.at(0, 2 * y + 1);
      std::uint8_t* q = out.at(0, y);
      for (int x = 0; x < w; ++x, r0 += 8, r1 += 8, q += 4) {
        for (int c = 0; c < 4; ++c) {
          const unsigned sum = 0u + r0[c] + r0[4 + c] + r1[c] + r1[4 + c];
          q[c] = static_cast<std::uint8_t>((sum + 2u) / 4u);
        }
      }
    }
    return out;
  }
  const double sx = static_cast<double>(image.width) / w;
  const double sy = static_cast<double>(image.height) / h;
  for (int y = 0; y < h; ++y) {
    const int y0 = static_cast<int>(y * sy);
    const int y1 = std::max(y0 + 1, std::min(image.height, static_cast<int>((y + 1) * sy)));
    for (int x = 0; x < w; ++x) {
      const int x0 = static_cast<int>(x * sx);
      const int x1 = std::max(x0 + 1, std::min(image.width, static_cast<int>((x + 1) * sx)));
      unsigned sum[4] = {0, 0, 0, 0};
      for (int yy = y0; yy < y1; ++yy) {
        for (int xx = x0; xx < x1; ++xx) {
          const std::uint8_t* p = image.at(xx, yy);
          for (int c = 0; c < 4; ++c) sum[c] += p[c];
        }
      }
      const unsigned n = static_cast<unsigned>((y1 - y0) * (x1 - x0));
      std::uint8_t* q = out.at(x, y);
      for (int c = 0; c < 4; ++c) q[c] = static_cast<std::uint8_t>((sum[c] + n / 2) / n);
    }
  }
  return out;
}

std::uint64_t HashImage(const Image& image) {
  std::uint64_t h = 1469598103934665603ull;
  auto mix = [&h](std::uint8_t b) {
    h ^= b;
    h *= 1099511628211ull;
  };
  for (int v : {image.width, image.height}) {
    for (int k = 0; k < 4; ++k) mix(static_cast<std::uint8_t>(v >> (8 * k)));
  }
  for (std::uint8_t b : image.rgba) mix(b);
  return h;
}

}  // namespace render
