// Figure formats and writing (see figure.h).
#include "render/figure.h"

#include "base/file_write.h"
#include "base/numbers.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <stdexcept>

namespace render {

const char* FigureFormatName(FigureFormat format) {
  switch (format) {
    case FigureFormat::kSvg:
      return "svg";
    case FigureFormat::kPdf:
      return "pdf";
    case FigureFormat::kPng:
      break;
  }
  return "png";
}

namespace {

bool FormatFromName(std::string name, FigureFormat* out) {
  std::transform(name.begin(), name.end(), name.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  for (FigureFormat f : {FigureFormat::kPng, FigureFormat::kSvg, FigureFormat::kPdf}) {
    if (name == FigureFormatName(f)) {
      *out = f;
      return true;
    }
  }
  return false;
}

}  // namespace

FigureFormat FigureFormatForPath(const std::string& path, const std::string& flag) {
  const std::string ext = std::filesystem::path(path).extension().string();
  FigureFormat f = FigureFormat::kPng;
  if (ext.size() < 2 || !FormatFromName(ext.substr(1), &f)) {
    throw std::invalid_argument(flag + ": '" + path +
                                "': the file name must end in .png, .svg or .pdf (the format)");
  }
  return f;
}

std::vector<FigureFormat> ParseFigureFormats(const std::string& list, const std::string& flag) {
  std::vector<FigureFormat> out;
  size_t start = 0;
  while (start <= list.size()) {
    const size_t comma = std::min(list.find(',', start), list.size());
    const std::string name = list.substr(start, comma - start);
    FigureFormat f = FigureFormat::kPng;
    if (!FormatFromName(name, &f)) {
      throw std::invalid_argument(flag + ": unknown figure format '" + name +
                                  "' (expected a comma-separated subset of png,svg,pdf)");
    }
    if (std::find(out.begin(), out.end(), f) == out.end()) out.push_back(f);
    start = comma + 1;
  }
  return out;
}

std::string PathWithFormat(const std::string& path, FigureFormat format) {
  return std::filesystem::path(path).replace_extension(FigureFormatName(format)).string();
}

std::string FormatNumber(double v, int decimals, bool plus) {
  if (!std::isfinite(v)) return std::isnan(v) ? "nan" : (v > 0 ? "\u221e" : "\u2212\u221e");
  const std::string digits = base::FormatFixed(std::abs(v), std::clamp(decimals, 0, 17));
  // Negative only when some digit survives the rounding (no "−0.000").
  const bool zero = digits.find_first_not_of("0.") == std::string::npos;
  if (v < 0.0 && !zero) return "\u2212" + digits;
  return (plus && !zero ? "+" : "") + digits;
}

std::string XmlEscape(std::string_view s) {
  // Well-formed XML whatever the bytes: the five markup characters escaped, control characters
  // (XML 1.0 allows only tab, newline and carriage return) and bytes that are not valid UTF-8
  // replaced by U+FFFD.
  static const std::string kReplacement = "\xEF\xBF\xBD";
  std::string out;
  const auto* p = reinterpret_cast<const unsigned char*>(s.data());
  const std::size_t n = s.size();
  for (std::size_t i = 0; i < n;) {
    const unsigned char c = p[i];
    if (c < 0x80) {
      if (c == '<') {
        out += "&lt;";
      } else if (c == '>') {
        out += "&gt;";
      } else if (c == '&') {
        out += "&amp;";
      } else if (c == '"') {
        out += "&quot;";
      } else if ((c < 0x20 && c != '\t' && c != '\n' && c != '\r') || c == 0x7f) {
        out += kReplacement;
      } else {
        out += static_cast<char>(c);
      }
      ++i;
      continue;
    }
    // A UTF-8 sequence: its length from the lead byte, continuation bytes 10xxxxxx, no overlong
    // forms, no surrogates, at most U+10FFFF.
    const std::size_t len = (c >= 0xF0 && c <= 0xF4)   ? 4
                            : (c >= 0xE0 && c <= 0xEF) ? 3
                            : (c >= 0xC2 && c <= 0xDF) ? 2
                                                       : 0;
    bool ok = len > 0 && i + len <= n;
    for (std::size_t k = 1; ok && k < len; ++k) ok = (p[i + k] & 0xC0) == 0x80;
    if (ok && len == 3) {
      ok = !(c == 0xE0 && p[i + 1] < 0xA0) && !(c == 0xED && p[i + 1] >= 0xA0);
    }
    if (ok && len == 4) ok = !(c == 0xF0 && p[i + 1] < 0x90) && !(c == 0xF4 && p[i + 1] >= 0x90);
    if (!ok) {
      out += kReplacement;
      ++i;
      continue;
    }
    out.append(reinterpret_cast<const char*>(p + i), len);
    i += len;
  }
  return out;
}

Figure::Figure(std::function<Image()> raster, std::function<std::string(FigureFormat)> vector)
    : raster_(std::move(raster)), vector_(std::move(vector)) {}

std::string Figure::Encode(FigureFormat format) const {
  if (format == FigureFormat::kPng) return EncodePng(raster_());
  return vector_(format);
}

void WriteFigure(const std::string& path, const Figure& figure, const std::string& flag) {
  base::WriteFileAtomic(path, figure.Encode(FigureFormatForPath(path, flag)));
}

std::vector<std::string> WriteFigureFormats(const std::string& path, const Figure& figure,
                                            const std::vector<FigureFormat>& formats) {
  std::vector<std::string> written;
  for (FigureFormat f : formats) {
    written.push_back(PathWithFormat(path, f));
    base::WriteFileAtomic(written.back(), figure.Encode(f));
  }
  return written;
}

}  // namespace render
