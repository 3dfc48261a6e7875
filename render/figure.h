// Figures in any output format: PNG (raster, the pixels the goldens compare), SVG and PDF
// (vector: heatmap cells as rectangles and labels as real text; plots through PLplot's cairo
// vector devices). A Figure is a small value that draws itself on demand in the asked format.
#pragma once

#include <functional>
#include <string>
#include <string_view>
#include <vector>

#include "render/image.h"

namespace render {

enum class FigureFormat { kPng, kSvg, kPdf };

// "png", "svg", "pdf": the format's name and file extension (without the dot).
const char* FigureFormatName(FigureFormat format);

// The format named by the extension of `path` (.png, .svg, .pdf; case-insensitive). Throws
// std::invalid_argument naming `flag` and the path for any other extension.
FigureFormat FigureFormatForPath(const std::string& path, const std::string& flag);

// Parses a comma-separated list such as "png,svg,pdf" (each at most once, order kept). Throws
// std::invalid_argument naming `flag` for an empty list or an unknown name.
std::vector<FigureFormat> ParseFigureFormats(const std::string& list, const std::string& flag);

// `path` with its extension replaced by the format's (fig.png -> fig.svg).
std::string PathWithFormat(const std::string& path, FigureFormat format);

// Formats v with `decimals` digits after the point for figure text: U+2212 for negatives, never
// a negative zero (−0.0004 at 3 decimals is "0.000"), and "+" before positives when `plus`.
std::string FormatNumber(double v, int decimals, bool plus = false);

// `s` with <, >, & and " escaped for XML/HTML text and attribute values.
std::string XmlEscape(std::string_view s);

class Figure {
 public:
  // raster: the PNG pixels; vector: SVG text (kSvg) or PDF bytes (kPdf).
  Figure(std::function<Image()> raster, std::function<std::string(FigureFormat)> vector);

  Image Raster() const { return raster_(); }
  // The file contents in `format`: PNG bytes (EncodePng of Raster()), SVG text or PDF bytes.
  std::string Encode(FigureFormat format) const;

 private:
  std::function<Image()> raster_;
  std::function<std::string(FigureFormat)> vector_;
};

// Writes the figure to `path` (atomically) in the format named by its extension
// (FigureFormatForPath; `flag` names the flag in errors).
void WriteFigure(const std::string& path, const Figure& figure, const std::string& flag = "-o");

// Writes `path` once per format with the extension replaced (PathWithFormat); returns the paths.
std::vector<std::string> WriteFigureFormats(const std::string& path, const Figure& figure,
                                            const std::vector<FigureFormat>& formats);

}  // namespace render
