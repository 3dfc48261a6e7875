// Line, scatter and grouped-bar plots rendered offscreen with PLplot (Debian libplplot + its
// cairo driver: "memcairo" draws anti-aliased lines and real text into memory for PNG;
// "svgcairo"/"pdfcairo" write the same plot as SVG or a one-page PDF). Used for Fig. 4.5
// (panels over the angle to unwrap, log y, median and interquartile band per planner, failure
// markers), writhe and cost over time, and the grasp summary. No GL context needed.
//
// Tick labels use U+2212 for negatives and never show a negative zero.
//
// Look: white background, black frame with outward-free inward ticks on all four sides, light grey
// grid at major ticks, title above, axis labels, legend box in the top-left corner (or where
// asked), series in the matplotlib "tab10" colours.
#pragma once

#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <string>
#include <utility>
#include <vector>

#include "render/figure.h"
#include "render/image.h"

namespace render {

enum class Marker { kNone, kCircle, kSquare, kTriangle, kDiamond };

struct PlotSeries {
  // PlotSeries{"label", x, y}, or default construction and member-wise assignment.
  PlotSeries(std::string label_ = {}, std::vector<double> x_ = {}, std::vector<double> y_ = {})
      : label(std::move(label_)), x(std::move(x_)), y(std::move(y_)) {}

  std::string label;      // legend text; empty: not in the legend
  std::vector<double> x;  // same length as y; non-finite points (and y <= 0 on a log axis) are
  std::vector<double> y;  // skipped and break the line
  bool line = true;       // connect the points
  Marker marker = Marker::kCircle;
  // Colour; alpha 0 (the default) picks tab10 colour number <series index> mod 10.
  std::array<std::uint8_t, 4> rgba{0, 0, 0, 0};
  // Runs that failed at these x positions: drawn as a cross in the series colour, at failure_y
  // when it has the same length, else along the top edge of the plot. One "failed" entry is
  // added to the legend when any series has failures.
  std::vector<double> failure_x;
  std::vector<double> failure_y;
  // Optional band around the line (e.g. the interquartile range): empty, or y_lo and y_hi with
  // x's length; filled translucent in the series colour; a non-finite end breaks the band.
  std::vector<double> y_lo;
  std::vector<double> y_hi;
};

// kOutsideRight: to the right of the axes (the plot area shrinks to make room).
enum class LegendPosition { kTopLeft, kTopRight, kBottomLeft, kBottomRight, kOutsideRight, kNone };

struct PlotOptions {
  int width = 640;  // pixels, >= 160 x 120
  int height = 480;
  std::string title, x_label, y_label;
  bool log_y = false;  // base-10 y axis with decade ticks (10^k labels)
  // Axis limits; NaN: from the data (x: exact data range; y: decades on a log axis, nice round
  // numbers on a linear one).
  double x_min = std::numeric_limits<double>::quiet_NaN();
  double x_max = std::numeric_limits<double>::quiet_NaN();
  double y_min = std::numeric_limits<double>::quiet_NaN();
  double y_max = std::numeric_limits<double>::quiet_NaN();
  LegendPosition legend = LegendPosition::kTopLeft;
};

// The tab10 colour number i (0..9, wraps).
std::array<std::uint8_t, 3> SeriesColor(int i);

// Renders the plot. Throws std::invalid_argument for a series whose x and y lengths differ (or
// a band of another length), a figure below 160x120, or no finite point at all (and no explicit
// limits).
Image RenderPlot(const std::vector<PlotSeries>& series, const PlotOptions& options);
// The same plot in any format (throws as RenderPlot when encoded).
Figure PlotFigure(const std::vector<PlotSeries>& series, const PlotOptions& options);

// Several plots with their own axes on one page (one PDF page): panels fill a grid of
// `columns` columns row by row under an optional figure title. Each panel's PlotOptions gives
// its title, labels, scale, limits and legend (its width/height are ignored). Series colours
// are per panel (tab10 by index unless rgba is set), so a planner keeps its colour across
// panels when it has the same index.
struct PlotPanel {
  std::vector<PlotSeries> series;
  PlotOptions axes;
};
struct PanelLayout {
  int width = 640;  // pixels, >= 160 x 120
  int height = 480;
  int columns = 1;
  std::string title;
};
Figure PanelsFigure(const std::vector<PlotPanel>& panels, const PanelLayout& layout);

// Grouped bars: one group per category (named on the x axis; long names are written upwards),
// one bar per series in each group, in the series' colour, with an optional interval whisker
// [lo, hi] per bar.
struct BarSeries {
  std::string label;           // legend text
  std::vector<double> values;  // one per category; NaN: no bar
  // Interval per bar: both empty, or one entry per category (NaN: no whisker for that bar).
  std::vector<double> lo, hi;
  std::array<std::uint8_t, 4> rgba{0, 0, 0, 0};  // alpha 0: tab10 colour <series index>
};
struct BarChart {
  std::vector<std::string> categories;
  std::vector<BarSeries> series;
};
// options: size, title, x/y labels, y limits (default: [0, nice max of values and whiskers]),
// legend position (log_y and x limits are ignored). Throws std::invalid_argument when a series'
// values (or lo/hi) do not have one entry per category, or there is no category.
Figure BarChartFigure(const BarChart& chart, const PlotOptions& options);

}  // namespace render
