// Grouped bar charts (BarChartFigure, see plot.h) drawn with PLplot: one group per category
// spanning 0.8 of a category's width on the x axis, one bar per series in the group (with an
// optional interval whisker), category names under the axis (written upwards when they do not
// fit their group), and a legend of colour boxes.
#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

#include "render/internal/plplot_figure.h"
#include "render/internal/text.h"
#include "render/plot.h"

namespace render {
namespace {

using internal::Box;
using internal::kFirstSeriesSlot;
using internal::kGridSlot;
using internal::kInkSlot;
using internal::Rgb;
using internal::TextScale;

// Throws std::invalid_argument unless every series has one value (and lo/hi, if any) per
// category. Returns the series colours (rgba, or tab10 by index when alpha is 0) and sets *top
// to the largest finite value or hi (0 when none is positive).
std::vector<Rgb> CheckBars(const BarChart& chart, double* top) {
  const size_t nc = chart.categories.size(), ns = chart.series.size();
  std::vector<Rgb> colors;
  for (size_t s = 0; s < ns; ++s) {
    const BarSeries& b = chart.series[s];
    if (b.values.size() != nc || b.lo.size() != b.hi.size() ||
        (!b.lo.empty() && b.lo.size() != nc)) {
      throw std::invalid_argument("bar chart: series " + std::to_string(s) + " ('" + b.label +
                                  "') needs one value (and lo/hi, if any) per category (" +
                                  std::to_string(nc) + ")");
    }
    for (double v : b.values) {
      if (std::isfinite(v)) *top = std::max(*top, v);
    }
    for (double v : b.hi) {
      if (std::isfinite(v)) *top = std::max(*top, v);
    }
    colors.push_back(b.rgba[3] == 0 ? SeriesColor(static_cast<int>(s))
                                    : Rgb{b.rgba[0], b.rgba[1], b.rgba[2]});
  }
  return colors;
}

// Where the axes go on the page and how the category names under them are written.
struct BarLayout {
  Box vp;          // axes viewport (normalised page coordinates)
  bool upright;    // category names written upwards (the widest does not fit its group)
  double label_h;  // pixels under the axes taken by the category names
};

BarLayout LayOutBars(const BarChart& chart, const PlotOptions& o, const TextScale& ts) {
  const size_t nc = chart.categories.size();
  // Category names: horizontal when they fit their group, else written upwards.
  const internal::Font& font = internal::Font::Regular();
  float widest = 0.0f;
  for (const std::string& c : chart.categories) {
    widest = std::max(widest, font.Width(c, static_cast<float>(1.3 * ts.px)));
  }
  double right = 1.0 - 1.6 * ts.px / o.width;
  const double left = 6.4 * ts.px / o.width;
  if (o.legend == LegendPosition::kOutsideRight) {
    std::vector<std::string> labels;
    for (const BarSeries& b : chart.series) labels.push_back(b.label);
    right -= internal::OutsideLegendWidth(labels, ts, o.width, right - left);
  }
  const bool upright = widest > 0.9 * (right - left) * o.width / static_cast<double>(nc);
  const double label_h = upright ? widest + 1.5 * ts.px : 1.6 * ts.px;
  const Box vp{left, right, (label_h + 3.4 * ts.px) / o.height,
               1.0 - (o.title.empty() ? 1.2 : 2.6) * ts.px / o.height};
  return {vp, upright, label_h};
}

// Bars from 0 to each value and whiskers [lo, hi] with caps, all clamped to [y_lo, y_hi]; category
// c (0-based) is centred at x = c + 1.
void DrawBarGroups(const BarChart& chart, double y_lo, double y_hi) {
  const size_t nc = chart.categories.size(), ns = chart.series.size();
  // Bars: the group spans 0.8 of a category; whiskers with caps over each bar.
  const double group = 0.8, bar = group / std::max<size_t>(ns, 1);
  for (size_t s = 0; s < ns; ++s) {
    const BarSeries& b = chart.series[s];
    for (size_t c = 0; c < nc; ++c) {
      const double x0 = (c + 1) - 0.5 * group + s * bar, x1 = x0 + bar;
      const double v = b.values[c];
      if (std::isfinite(v)) {
        const double yv = std::clamp(v, y_lo, y_hi), yb = std::clamp(0.0, y_lo, y_hi);
        double px[4] = {x0, x1, x1, x0}, py[4] = {yb, yb, yv, yv};
        plcol0(kFirstSeriesSlot + static_cast<int>(s));
        plfill(4, px, py);
        plcol0(kInkSlot);
        plwidth(0.5);
        double ox[5] = {x0, x1, x1, x0, x0}, oy[5] = {yb, yb, yv, yv, yb};
        plline(5, ox, oy);
      }
      if (!b.lo.empty() && std::isfinite(b.lo[c]) && std::isfinite(b.hi[c])) {
        const double xm = 0.5 * (x0 + x1), cap = 0.25 * bar;
        const double l = std::clamp(b.lo[c], y_lo, y_hi), h = std::clamp(b.hi[c], y_lo, y_hi);
        plcol0(kInkSlot);
        plwidth(1.2);
        pljoin(xm, l, xm, h);
        pljoin(xm - cap, l, xm + cap, l);
        pljoin(xm - cap, h, xm + cap, h);
      }
    }
  }
}

// Category names under the axes, the x and y axis labels and the title.
void DrawBarLabels(const BarChart& chart, const PlotOptions& o, const TextScale& ts,
                   const BarLayout& layout) {
  const size_t nc = chart.categories.size();
  for (size_t c = 0; c < nc; ++c) {
    const double pos = (static_cast<double>(c) + 0.5) / nc;
    if (layout.upright) {
      plmtex("bv", 0.6, pos, 1.0, chart.categories[c].c_str());
    } else {
      plmtex("b", 1.5, pos, 0.5, chart.categories[c].c_str());
    }
  }
  plmtex("b", (layout.label_h + 1.6 * ts.px) / (ts.px * 1.0) * 0.75, 0.5, 0.5, o.x_label.c_str());
  plmtex("l", 3.6, 0.5, 0.5, o.y_label.c_str());
  if (!o.title.empty()) {
    plschr(0.0, 1.2 * ts.scale);
    plmtex("t", 1.2, 0.5, 0.5, o.title.c_str());
    plschr(0.0, ts.scale);
  }
}

// One colour box per series.
internal::LegendEntries BarLegend(const BarChart& chart) {
  internal::LegendEntries e;
  for (size_t s = 0; s < chart.series.size(); ++s) {
    e.opts.push_back(PL_LEGEND_COLOR_BOX);
    e.texts.push_back(chart.series[s].label.c_str());
    e.symbols.push_back("");
    e.line_colors.push_back(kInkSlot);
    e.symbol_colors.push_back(kInkSlot);
    e.box_colors.push_back(kFirstSeriesSlot + static_cast<int>(s));
  }
  return e;
}

// The chart on the current PLplot page with y axis [y_lo, y_hi].
void DrawBarChart(const BarChart& chart, const PlotOptions& o, double y_lo, double y_hi) {
  const TextScale ts = internal::TextScaleFor(o.width, o.height);
  plschr(0.0, ts.scale);
  const BarLayout layout = LayOutBars(chart, o, ts);
  const Box& vp = layout.vp;
  plvpor(vp.x0, vp.x1, vp.y0, vp.y1);
  // 4% headroom: bars and whiskers at the top value stay clear of the frame.
  plwind(0.5, chart.categories.size() + 0.5, y_lo, y_hi + 0.04 * (y_hi - y_lo));
  internal::LabelFormat labels;
  labels.y = internal::LinearStep(
      y_lo, y_hi, std::max(2, static_cast<int>((vp.y1 - vp.y0) * o.height / (4.0 * ts.px))));
  plslabelfunc(internal::FormatTickLabel, &labels);
  plcol0(kGridSlot);
  plwidth(0.6);
  plbox("", 0.0, 0, "g", labels.y.step, 0);
  DrawBarGroups(chart, y_lo, y_hi);
  plcol0(kInkSlot);
  plwidth(1.0);
  plbox("bc", 0.0, 0, "bcnstvo", labels.y.step, 0);
  DrawBarLabels(chart, o, ts, layout);
  internal::DrawLegend(BarLegend(chart), o.legend, ts);
}

void DrawBars(const BarChart& chart, const PlotOptions& o, FigureFormat format, Image* image,
              std::string* bytes) {
  internal::CheckFigureSize(o.width, o.height, "bar chart");
  if (chart.categories.empty()) throw std::invalid_argument("bar chart: no category");
  double top = 0.0;
  const std::vector<Rgb> colors = CheckBars(chart, &top);
  double y_lo = std::isfinite(o.y_min) ? o.y_min : 0.0;
  double y_hi = std::isfinite(o.y_max) ? o.y_max : top;
  if (!std::isfinite(o.y_max)) internal::NiceRange(&y_lo, &y_hi);
  if (!(y_hi > y_lo)) y_hi = y_lo + 1.0;
  internal::RunPlplot(
      o.width, o.height, format, colors, [&] { DrawBarChart(chart, o, y_lo, y_hi); }, image, bytes);
}

}  // namespace

Figure BarChartFigure(const BarChart& chart, const PlotOptions& options) {
  return internal::PlplotFigure([chart, options](FigureFormat f, Image* image, std::string* bytes) {
    DrawBars(chart, options, f, image, bytes);
  });
}

}  // namespace render
