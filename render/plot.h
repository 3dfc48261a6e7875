// Line and scatter plots rendered offscreen with PLplot (Debian libplplot + its cairo driver,
// "memcairo" device: anti-aliased lines and real text drawn into memory). Used for "collision
// checks vs angle to unwrap" (log y, one curve per planner, failure markers) and "AICO cost per
// sweep". No GL context needed.
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
};

enum class LegendPosition { kTopLeft, kTopRight, kBottomLeft, kBottomRight, kNone };

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

// Renders the plot. Throws std::invalid_argument for a series whose x and y lengths differ, a
// figure below 160x120, or no finite point at all (and no explicit limits).
Image RenderPlot(const std::vector<PlotSeries>& series, const PlotOptions& options);

}  // namespace render
