// PLplot plumbing and the look every plot shares (line plots, panels and bar charts in plot.cc and
// plot_bars.cc): one PLplot stream per figure on the device of the output format, colour-map-0
// slots, the text scale, linear tick steps and their labels (U+2212 minus, 10^k on log axes),
// nice axis ranges, the legend, and a Figure that draws itself through PLplot on demand.
#pragma once

#include <plplot.h>

#include <functional>
#include <string>
#include <vector>

#include "render/figure.h"
#include "render/image.h"
#include "render/internal/canvas.h"
#include "render/plot.h"

namespace render::internal {

// PLplot colour-map-0 slots: 0 background, 1 ink, 2 grid, 3.. series, then their band colours.
constexpr int kInkSlot = 1, kGridSlot = 2, kFirstSeriesSlot = 3;

// Throws std::invalid_argument "<what>: figure size WxH is below the minimum 160x120".
void CheckFigureSize(int width, int height, const char* what);

// Widens [*lo, *hi] to a nice linear range: 2% of the span added at each non-zero end, then both
// ends rounded outwards to multiples of half the span's power of ten. An empty or reversed range
// is padded by 10% of |lo| (1 when lo is 0) on each side instead.
void NiceRange(double* lo, double* hi);

// Major tick step of a linear axis over [lo, hi] (about `target` intervals; 1, 2, 2.5, 5 x 10^k)
// and the decimals its labels need.
struct TickStep {
  double step = 0.0;  // 0: let PLplot choose (log axes)
  int decimals = 0;
};
TickStep LinearStep(double lo, double hi, int target);

// Tick labels of one panel: fixed decimals per linear axis, 10^k on a log axis, U+2212 minus.
struct LabelFormat {
  TickStep x, y;
  bool log_y = false;
};
// PLplot label callback (plslabelfunc) with `data` a LabelFormat that outlives the plbox calls.
void FormatTickLabel(PLINT axis, PLFLT value, char* label, PLINT length, PLPointer data);

// Text height (pixels) and PLplot character scale. PLplot sizes characters in proportion to the
// page's width + height, so the scale is computed from the 4:3 page of the same width + height
// (h_eq); the text grows slowly with the size of one set of axes `ref_w` x `ref_h` (about 11 px
// at 640x480, 9 px at 320x240).
struct TextScale {
  double scale, px;
};
TextScale TextScaleFor(int width, int height, double ref_w, double ref_h);
TextScale TextScaleFor(int width, int height);

// Viewport of a panel in normalised page coordinates.
struct Box {
  double x0, x1, y0, y1;
};

// Legend entries of a panel, drawn with pllegend.
struct LegendEntries {
  std::vector<PLINT> opts, line_colors, symbol_colors, box_colors;
  std::vector<const char*> texts, symbols;
};
// Draws the entries (nothing when there are none or `where` is kNone) in the current viewport.
void DrawLegend(const LegendEntries& e, LegendPosition where, const TextScale& ts);

// Room (normalised page width) a legend outside on the right needs when the axes would otherwise
// span `span` (normalised page width). pllegend places it 0.02 viewport widths right of the axes
// and gives its symbols 0.08 viewport widths, so with the viewport span − room wide the room r
// solves r = 0.10·(span − r) + text + margins.
double OutsideLegendWidth(const std::vector<std::string>& labels, const TextScale& ts, int width,
                          double span);

// Runs `draw` in a fresh PLplot stream on the device of `format`, with colour slots 3.. set to
// `colors` and the next ones to the same colours at 25% opacity (bands). PNG: returns the
// pixels in *image; SVG/PDF: the file bytes in *bytes.
void RunPlplot(int width, int height, FigureFormat format, const std::vector<Rgb>& colors,
               const std::function<void()>& draw, Image* image, std::string* bytes);

// A Figure whose PNG and vector encodings come from draw(format, Image*, std::string*).
template <typename Draw>
Figure PlplotFigure(Draw draw) {
  return Figure(
      [draw] {
        Image image;
        draw(FigureFormat::kPng, &image, nullptr);
        return image;
      },
      [draw](FigureFormat format) {
        std::string bytes;
        draw(format, nullptr, &bytes);
        return bytes;
      });
}

}  // namespace render::internal
