// One set of axes of line/marker series drawn with PLplot (a single plot or one panel of a
// page): data ranges (log10 on a log y axis), frame, grid, tick and axis labels, translucent
// bands, lines broken at unplottable points, markers, failure crosses and the legend.
#pragma once

#include <vector>

#include "render/internal/plplot_figure.h"
#include "render/plot.h"

namespace render::internal {

// Data ranges of one set of axes (axis coordinates: log10 on a log y axis); x_pad widens the
// x window on both sides so markers on the frame are not cut in half.
struct Axes {
  double x_lo, x_hi, y_lo, y_hi, x_pad;
  bool any_failure;
};

// The axes of `series` under the limits of `o`. Throws std::invalid_argument for a series whose
// x and y lengths differ, a band of another length, or no finite point and no explicit limits.
Axes ComputeAxes(const std::vector<PlotSeries>& series, const PlotOptions& o);

// The colour of each series: its rgba when alpha is not 0, else tab10 by index.
std::vector<Rgb> ColorsOf(const std::vector<PlotSeries>& series);

// One panel of line/marker series in viewport `vp` of a width x height page; colour slots
// slot0.. (lines) and band_slot0.. (bands).
void DrawSeriesPanel(const std::vector<PlotSeries>& series, const PlotOptions& o, const Box& vp,
                     const TextScale& ts, int width, int height, int slot0, int band_slot0);

}  // namespace render::internal
