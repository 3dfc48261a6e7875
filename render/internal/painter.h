// One drawing interface for figures drawn by our own code (heatmaps), with three back ends: a
// raster Image (whole-pixel rectangles, stb_truetype text), SVG text (one <rect> per rectangle,
// <text> for labels) and PDF (cairo). Coordinates are pixels of the figure, y down; a pixel is
// one SVG user unit and one PDF point.
#pragma once

#include <memory>
#include <string>
#include <string_view>

#include "render/image.h"
#include "render/internal/canvas.h"
#include "render/internal/text.h"

namespace render::internal {

class Painter {
 public:
  virtual ~Painter() = default;
  // Fills [x0, x1) x [y0, y1). `tag`, when given, becomes the SVG class (e.g. "cell").
  virtual void Fill(int x0, int y0, int x1, int y1, const Rgb& rgb, const char* tag = nullptr) = 0;
  // Outline `width` pixels wide lying inside [x0, x1) x [y0, y1).
  virtual void Stroke(int x0, int y0, int x1, int y1, const Rgb& rgb, int width = 1) = 0;
  // Text with its baseline at y; x is its left end, centre or right end per `align`. `px` is the
  // text height as in Font (ascent − descent).
  virtual void Text(float x, float y, std::string_view text, float px, const Rgb& rgb, Align align,
                    bool bold = false) = 0;
  // Text reading upwards, centred at (cx, cy).
  virtual void VerticalText(float cx, float cy, std::string_view text, float px,
                            const Rgb& rgb) = 0;
};

// Draws into `image` (not owned).
std::unique_ptr<Painter> MakeRasterPainter(Image* image);

// A vector document of width x height pixels; Finish() returns the file contents.
class VectorPainter : public Painter {
 public:
  virtual std::string Finish() = 0;
};
std::unique_ptr<VectorPainter> MakeSvgPainter(int width, int height);
// PDF through cairo, one page; fixed creation date so that the bytes are reproducible.
std::unique_ptr<VectorPainter> MakePdfPainter(int width, int height);

}  // namespace render::internal
