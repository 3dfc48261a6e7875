// Perceptual image diff and golden-image checks (see diff.h).
#include "render/diff.h"

#include "base/numbers.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <stdexcept>

namespace render {
namespace {

struct Yiq {
  double y, i, q;
};

// Colour of pixel p blended over white by its alpha, in YIQ.
Yiq ToYiq(const std::uint8_t* p) {
  double r = p[0], g = p[1], b = p[2];
  if (p[3] < 255) {
    const double a = p[3] / 255.0;
    r = 255.0 + (r - 255.0) * a;
    g = 255.0 + (g - 255.0) * a;
    b = 255.0 + (b - 255.0) * a;
  }
  return {r * 0.29889531 + g * 0.58662247 + b * 0.11448223,
          r * 0.59597799 - g * 0.27417610 - b * 0.32180189,
          r * 0.21147017 - g * 0.52261711 + b * 0.31114694};
}

bool SamePixel(const std::uint8_t* a, const std::uint8_t* b) {
  return a[0] == b[0] && a[1] == b[1] && a[2] == b[2] && a[3] == b[3];
}

// Signed squared YIQ distance (negative when the second colour is brighter).
double ColorDelta(const std::uint8_t* a, const std::uint8_t* b) {
  if (SamePixel(a, b)) return 0.0;
  const Yiq ya = ToYiq(a), yb = ToYiq(b);
  const double dy = ya.y - yb.y, di = ya.i - yb.i, dq = ya.q - yb.q;
  const double d = 0.5053 * dy * dy + 0.299 * di * di + 0.1957 * dq * dq;
  return ya.y > yb.y ? -d : d;
}

double BrightnessDelta(const std::uint8_t* a, const std::uint8_t* b) {
  if (SamePixel(a, b)) return 0.0;
  return ToYiq(a).y - ToYiq(b).y;
}

// More than 2 of the (up to 8) neighbours of (x, y) equal it; pixels on the border count one
// extra identical neighbour.
bool HasManySiblings(const Image& img, int x, int y) {
  const int x0 = std::max(x - 1, 0), y0 = std::max(y - 1, 0);
  const int x1 = std::min(x + 1, img.width - 1), y1 = std::min(y + 1, img.height - 1);
  int zeroes = (x == x0 || x == x1 || y == y0 || y == y1) ? 1 : 0;
  for (int yy = y0; yy <= y1; ++yy) {
    for (int xx = x0; xx <= x1; ++xx) {
      if (xx == x && yy == y) continue;
      if (SamePixel(img.at(x, y), img.at(xx, yy)) && ++zeroes > 2) return true;
    }
  }
  return false;
}

// Whether (x, y) of `img` looks like an anti-aliased edge pixel (see diff.h); `other` is the
// second image.
bool AntiAliased(const Image& img, int x, int y, const Image& other) {
  const int x0 = std::max(x - 1, 0), y0 = std::max(y - 1, 0);
  const int x1 = std::min(x + 1, img.width - 1), y1 = std::min(y + 1, img.height - 1);
  int zeroes = (x == x0 || x == x1 || y == y0 || y == y1) ? 1 : 0;
  double lo = 0.0, hi = 0.0;
  int lo_x = 0, lo_y = 0, hi_x = 0, hi_y = 0;
  for (int yy = y0; yy <= y1; ++yy) {
    for (int xx = x0; xx <= x1; ++xx) {
      if (xx == x && yy == y) continue;
      const double d = BrightnessDelta(img.at(x, y), img.at(xx, yy));
      if (d == 0.0) {
        if (++zeroes > 2) return false;
      } else if (d < lo) {
        lo = d, lo_x = xx, lo_y = yy;
      } else if (d > hi) {
        hi = d, hi_x = xx, hi_y = yy;
      }
    }
  }
  if (lo == 0.0 || hi == 0.0) return false;
  return (HasManySiblings(img, lo_x, lo_y) && HasManySiblings(other, lo_x, lo_y)) ||
         (HasManySiblings(img, hi_x, hi_y) && HasManySiblings(other, hi_x, hi_y));
}

void Put(Image* img, int x, int y, std::uint8_t r, std::uint8_t g, std::uint8_t b) {
  std::uint8_t* p = img->at(x, y);
  p[0] = r;
  p[1] = g;
  p[2] = b;
  p[3] = 255;
}

}  // namespace

long DefaultAllowedDiffPixels(int width, int height) {
  const double pixels = static_cast<double>(width) * height;
  return std::max(10L, static_cast<long>(std::ceil(pixels * 0.005 / 100.0)));
}

DiffResult CompareImages(const Image& expected, const Image& actual, const DiffOptions& options) {
  if (expected.width != actual.width || expected.height != actual.height) {
    throw std::invalid_argument("image sizes differ: expected " + std::to_string(expected.width) +
                                "x" + std::to_string(expected.height) + ", actual " +
                                std::to_string(actual.width) + "x" + std::to_string(actual.height));
  }
  if (!(options.threshold >= 0.0 && options.threshold <= 1.0)) {
    throw std::invalid_argument("diff threshold must be in [0, 1], got " +
                                base::FormatShortest(options.threshold));
  }
  DiffResult r;
  r.allowed = options.max_diff_pixels >= 0
                  ? options.max_diff_pixels
                  : DefaultAllowedDiffPixels(expected.width, expected.height);
  r.identical = expected.rgba == actual.rgba;
  r.visual = Image(expected.width, expected.height);
  const double max_delta = 35215.0 * options.threshold * options.threshold;
  for (int y = 0; y < expected.height; ++y) {
    for (int x = 0; x < expected.width; ++x) {
      const std::uint8_t* a = expected.at(x, y);
      const std::uint8_t* b = actual.at(x, y);
      if (!SamePixel(a, b)) {
        ++r.changed_pixels;
        for (int c = 0; c < 4; ++c) {
          r.max_channel_delta = std::max(r.max_channel_delta, std::abs(int{a[c]} - int{b[c]}));
        }
        const double d = ColorDelta(a, b);
        if (std::abs(d) > max_delta) {
          if (!options.include_aa &&
              (AntiAliased(expected, x, y, actual) || AntiAliased(actual, x, y, expected))) {
            ++r.aa_pixels;
            Put(&r.visual, x, y, 255, 220, 0);
          } else {
            ++r.diff_pixels;
            Put(&r.visual, x, y, 230, 0, 0);
          }
          continue;
        }
      }
      // Faded grey copy of the expected image.
      const double lum = ToYiq(a).y;
      const auto g = static_cast<std::uint8_t>(std::lround(255.0 + 0.1 * (lum - 255.0)));
      Put(&r.visual, x, y, g, g, g);
    }
  }
  r.passed = r.diff_pixels <= r.allowed;
  return r;
}

Image AmplifiedDifference(const Image& expected, const Image& actual, int gain) {
  if (expected.width != actual.width || expected.height != actual.height) {
    throw std::invalid_argument("AmplifiedDifference: image sizes differ");
  }
  Image out(expected.width, expected.height);
  for (size_t i = 0; i < out.rgba.size(); i += 4) {
    for (int c = 0; c < 3; ++c) {
      const int d = std::abs(int{expected.rgba[i + c]} - int{actual.rgba[i + c]}) * gain;
      out.rgba[i + c] = static_cast<std::uint8_t>(std::min(d, 255));
    }
  }
  return out;
}

SnapshotResult CheckSnapshot(const Image& actual, const std::string& golden_path,
                             const std::string& artefact_dir, const DiffOptions& options) {
  namespace fs = std::filesystem;
  SnapshotResult s;
  const std::string stem = fs::path(golden_path).stem().string();
  const fs::path dir(artefact_dir);
  const char* update = std::getenv("UPDATE_SNAPSHOTS");
  const bool exists = fs::is_regular_file(golden_path);
  if (update != nullptr && std::string(update) == "1") {
    if (!exists || !SameImage(ReadPng(golden_path), actual)) {
      WritePng(golden_path, actual, 9);
      s.updated = true;
      s.message = "UPDATE_SNAPSHOTS=1: wrote " + golden_path;
    } else {
      s.message = "UPDATE_SNAPSHOTS=1: " + golden_path + " already matches";
    }
    s.passed = true;
    return s;
  }
  if (!exists) {
    const std::string candidate = (dir / (stem + ".png")).string();
    WritePng(candidate, actual);
    s.message = "golden " + golden_path + " missing; candidate written to " + candidate +
                " (review it, then rerun with UPDATE_SNAPSHOTS=1)";
    return s;
  }
  const Image expected = ReadPng(golden_path);
  auto write_artefacts = [&]() {
    WritePng((dir / (stem + ".png")).string(), actual);
    WritePng((dir / (stem + "-expected.png")).string(), expected);
    return (dir / stem).string() + "{,-expected}.png";
  };
  if (expected.width != actual.width || expected.height != actual.height) {
    const std::string where = write_artefacts();
    s.message = "size mismatch: golden " + std::to_string(expected.width) + "x" +
                std::to_string(expected.height) + ", actual " + std::to_string(actual.width) + "x" +
                std::to_string(actual.height) + "; see " + where;
    return s;
  }
  s.diff = CompareImages(expected, actual, options);
  s.passed = s.diff.passed;
  if (s.diff.identical) {
    s.message = "identical to " + golden_path;
    return s;
  }
  std::string counts = std::to_string(s.diff.diff_pixels) + " different pixels (allowed " +
                       std::to_string(s.diff.allowed) + "), " + std::to_string(s.diff.aa_pixels) +
                       " anti-aliasing, " + std::to_string(s.diff.changed_pixels) +
                       " changed, max channel delta " + std::to_string(s.diff.max_channel_delta);
  if (!s.passed) {
    write_artefacts();
    WritePng((dir / (stem + "-diff.png")).string(), s.diff.visual);
    WritePng((dir / (stem + "-absdiff.png")).string(), AmplifiedDifference(expected, actual));
    counts += "; see " + (dir / stem).string() + "{,-expected,-diff,-absdiff}.png";
  }
  s.message = counts;
  return s;
}

}  // namespace render
