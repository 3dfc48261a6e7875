// Axes, bands, lines, markers, failures and legend of one panel of series (see plot_panel.h).
#include "render/internal/plot_panel.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

namespace render::internal {
namespace {

const char* MarkerGlyph(Marker m) {
  switch (m) {
    case Marker::kCircle:
      return "\u25cf";  // ●
    case Marker::kSquare:
      return "\u25a0";  // ■
    case Marker::kTriangle:
      return "\u25b2";  // ▲
    case Marker::kDiamond:
      return "\u25c6";  // ◆
    case Marker::kNone:
      break;
  }
  return "";
}
constexpr const char* kFailureGlyph = "\u2715";  // ✕

// Value as plotted on the y axis (log10 on a log axis; NaN when not plottable).
double AxisY(double y, bool log_y) {
  if (!std::isfinite(y)) return std::numeric_limits<double>::quiet_NaN();
  if (!log_y) return y;
  return y > 0.0 ? std::log10(y) : std::numeric_limits<double>::quiet_NaN();
}

// Throws std::invalid_argument unless series s has one y (and, with a band, one y_lo and y_hi)
// per x.
void CheckSeries(const PlotSeries& ps, size_t s) {
  if (ps.x.size() != ps.y.size()) {
    throw std::invalid_argument("plot: series " + std::to_string(s) + " ('" + ps.label + "') has " +
                                std::to_string(ps.x.size()) + " x values but " +
                                std::to_string(ps.y.size()) + " y values");
  }
  if (ps.y_lo.size() != ps.y_hi.size() || (!ps.y_lo.empty() && ps.y_lo.size() != ps.x.size())) {
    throw std::invalid_argument("plot: series " + std::to_string(s) + " ('" + ps.label +
                                "'): the band needs y_lo and y_hi with one value per x");
  }
}

// Frame, grid, tick labels, axis labels and panel title in viewport `vp` with window `axes`.
void DrawAxes(const PlotOptions& o, const Axes& a, const Box& vp, const TextScale& ts, int width,
              int height, bool x_numbers, LabelFormat* labels) {
  plvpor(vp.x0, vp.x1, vp.y0, vp.y1);
  plwind(a.x_lo - a.x_pad, a.x_hi + a.x_pad, a.y_lo, a.y_hi);
  const int x_target = std::max(2, static_cast<int>((vp.x1 - vp.x0) * width / (7.0 * ts.px)));
  const int y_target = std::max(2, static_cast<int>((vp.y1 - vp.y0) * height / (4.0 * ts.px)));
  labels->x = LinearStep(a.x_lo, a.x_hi, x_target);
  labels->y = o.log_y ? TickStep{} : LinearStep(a.y_lo, a.y_hi, y_target);
  labels->log_y = o.log_y;
  plslabelfunc(FormatTickLabel, labels);
  plcol0(kGridSlot);
  plwidth(0.6);
  plbox("g", labels->x.step, 0, o.log_y ? "gl" : "g", labels->y.step, 0);
  plcol0(kInkSlot);
  plwidth(1.0);
  plbox(x_numbers ? "bcnsto" : "bcst", labels->x.step, 0, o.log_y ? "bcnstlvo" : "bcnstvo",
        labels->y.step, 0);
  pllab(o.x_label.c_str(), o.y_label.c_str(), "");
  if (!o.title.empty()) {  // the title a little larger than the labels
    plschr(0.0, 1.2 * ts.scale);
    plmtex("t", 1.2, 0.5, 0.5, o.title.c_str());
    plschr(0.0, ts.scale);
  }
}

// The band [y_lo, y_hi] of `ps` filled in colour slot `slot`, clamped to the axes' y range and
// broken at non-finite ends.
void DrawBand(const PlotSeries& ps, bool log_y, const Axes& a, int slot) {
  plcol0(slot);
  std::vector<double> px, lo, hi;
  auto flush = [&]() {
    if (px.size() >= 2) {
      std::vector<double> xs(px), ys(lo);
      for (size_t k = px.size(); k-- > 0;) {
        xs.push_back(px[k]);
        ys.push_back(hi[k]);
      }
      plfill(static_cast<PLINT>(xs.size()), xs.data(), ys.data());
    }
    px.clear();
    lo.clear();
    hi.clear();
  };
  for (size_t k = 0; k < ps.x.size(); ++k) {
    const double l = AxisY(ps.y_lo[k], log_y), h = AxisY(ps.y_hi[k], log_y);
    if (!std::isfinite(ps.x[k]) || !std::isfinite(l) || !std::isfinite(h)) {
      flush();
      continue;
    }
    px.push_back(ps.x[k]);
    lo.push_back(std::clamp(l, a.y_lo, a.y_hi));
    hi.push_back(std::clamp(h, a.y_lo, a.y_hi));
  }
  flush();
}

// The line and markers of `ps` in colour slot `slot`, broken at unplottable points, then its
// failure crosses (at failure_y, else at axis height `top`).
void DrawSeries(const PlotSeries& ps, bool log_y, double top, int slot, const TextScale& ts) {
  std::vector<double> xs, ys;
  plcol0(slot);
  plwidth(2.0);
  auto flush = [&]() {
    if (ps.line && xs.size() >= 2) plline(static_cast<PLINT>(xs.size()), xs.data(), ys.data());
    if (ps.marker != Marker::kNone && !xs.empty()) {
      plstring(static_cast<PLINT>(xs.size()), xs.data(), ys.data(), MarkerGlyph(ps.marker));
    }
    xs.clear();
    ys.clear();
  };
  for (size_t k = 0; k < ps.x.size(); ++k) {
    const double ay = AxisY(ps.y[k], log_y);
    if (!std::isfinite(ps.x[k]) || !std::isfinite(ay)) {
      flush();
      continue;
    }
    xs.push_back(ps.x[k]);
    ys.push_back(ay);
  }
  flush();
  for (size_t k = 0; k < ps.failure_x.size(); ++k) {
    double fy = top;
    if (ps.failure_y.size() == ps.failure_x.size()) {
      const double ay = AxisY(ps.failure_y[k], log_y);
      if (std::isfinite(ay)) fy = ay;
    }
    const double fx = ps.failure_x[k];
    plschr(0.0, 1.3 * ts.scale);
    plstring(1, &fx, &fy, kFailureGlyph);
    plschr(0.0, ts.scale);
  }
}

// One legend entry per labelled series, plus "Failed run" when any failures are drawn.
LegendEntries SeriesLegend(const std::vector<PlotSeries>& series, bool any_failure, int slot0) {
  LegendEntries e;
  for (size_t s = 0; s < series.size(); ++s) {
    const PlotSeries& ps = series[s];
    if (ps.label.empty()) continue;
    const int slot = slot0 + static_cast<int>(s);
    PLINT opt = 0;
    if (ps.line) opt |= PL_LEGEND_LINE;
    if (ps.marker != Marker::kNone) opt |= PL_LEGEND_SYMBOL;
    e.opts.push_back(opt == 0 ? PL_LEGEND_NONE : opt);
    e.texts.push_back(ps.label.c_str());
    e.symbols.push_back(MarkerGlyph(ps.marker));
    e.line_colors.push_back(slot);
    e.symbol_colors.push_back(slot);
    e.box_colors.push_back(slot);
  }
  if (any_failure) {
    e.opts.push_back(PL_LEGEND_SYMBOL);
    e.texts.push_back("Failed run");
    e.symbols.push_back(kFailureGlyph);
    e.line_colors.push_back(kInkSlot);
    e.symbol_colors.push_back(kInkSlot);
    e.box_colors.push_back(kInkSlot);
  }
  return e;
}

}  // namespace

Axes ComputeAxes(const std::vector<PlotSeries>& series, const PlotOptions& o) {
  double x_lo = std::numeric_limits<double>::infinity(), x_hi = -x_lo;
  double y_lo = x_lo, y_hi = -x_lo;
  bool any_failure = false;
  auto take_y = [&](double y) {
    const double ay = AxisY(y, o.log_y);
    if (std::isfinite(ay)) {
      y_lo = std::min(y_lo, ay);
      y_hi = std::max(y_hi, ay);
    }
  };
  for (size_t s = 0; s < series.size(); ++s) {
    const PlotSeries& ps = series[s];
    CheckSeries(ps, s);
    for (size_t k = 0; k < ps.x.size(); ++k) {
      const double ay = AxisY(ps.y[k], o.log_y);
      if (!std::isfinite(ps.x[k]) || !std::isfinite(ay)) continue;
      x_lo = std::min(x_lo, ps.x[k]);
      x_hi = std::max(x_hi, ps.x[k]);
      take_y(ps.y[k]);
      if (!ps.y_lo.empty()) {
        take_y(ps.y_lo[k]);
        take_y(ps.y_hi[k]);
      }
    }
    for (size_t k = 0; k < ps.failure_x.size(); ++k) {
      any_failure = true;
      if (std::isfinite(ps.failure_x[k])) {
        x_lo = std::min(x_lo, ps.failure_x[k]);
        x_hi = std::max(x_hi, ps.failure_x[k]);
      }
      if (ps.failure_y.size() == ps.failure_x.size()) take_y(ps.failure_y[k]);
    }
  }
  if (std::isfinite(o.x_min)) x_lo = o.x_min;
  if (std::isfinite(o.x_max)) x_hi = o.x_max;
  if (std::isfinite(o.y_min)) y_lo = AxisY(o.y_min, o.log_y);
  if (std::isfinite(o.y_max)) y_hi = AxisY(o.y_max, o.log_y);
  if (!std::isfinite(x_lo) || !std::isfinite(x_hi) || !std::isfinite(y_lo) ||
      !std::isfinite(y_hi)) {
    throw std::invalid_argument("plot: no finite data point to plot and no axis limits given");
  }
  if (x_hi <= x_lo) {
    x_lo -= 0.5;
    x_hi += 0.5;
  }
  if (o.log_y) {
    if (!std::isfinite(o.y_min)) y_lo = std::floor(y_lo);
    if (!std::isfinite(o.y_max)) y_hi = std::ceil(y_hi);
    if (y_hi <= y_lo) y_hi = y_lo + 1.0;
  } else if (!std::isfinite(o.y_min) || !std::isfinite(o.y_max)) {
    NiceRange(&y_lo, &y_hi);
  }
  // Leave a little room so markers on the frame are not cut in half.
  const double x_pad = std::isfinite(o.x_min) ? 0.0 : 0.02 * (x_hi - x_lo);
  return {x_lo, x_hi, y_lo, y_hi, x_pad, any_failure};
}

std::vector<Rgb> ColorsOf(const std::vector<PlotSeries>& series) {
  std::vector<Rgb> colors;
  for (size_t s = 0; s < series.size(); ++s) {
    const auto& c = series[s].rgba;
    colors.push_back(c[3] == 0 ? SeriesColor(static_cast<int>(s)) : Rgb{c[0], c[1], c[2]});
  }
  return colors;
}

void DrawSeriesPanel(const std::vector<PlotSeries>& series, const PlotOptions& o, const Box& vp,
                     const TextScale& ts, int width, int height, int slot0, int band_slot0) {
  const Axes a = ComputeAxes(series, o);
  LabelFormat labels;
  DrawAxes(o, a, vp, ts, width, height, true, &labels);
  const int n_series = static_cast<int>(series.size());
  // Bands first (under the lines), broken at non-finite ends.
  for (int s = 0; s < n_series; ++s) {
    const PlotSeries& ps = series[static_cast<size_t>(s)];
    if (!ps.y_lo.empty()) DrawBand(ps, o.log_y, a, band_slot0 + s);
  }
  // Lines broken at unplottable points, then markers, then failures.
  const double top = a.y_hi - 0.03 * (a.y_hi - a.y_lo);
  for (int s = 0; s < n_series; ++s) {
    DrawSeries(series[static_cast<size_t>(s)], o.log_y, top, slot0 + s, ts);
  }
  DrawLegend(SeriesLegend(series, a.any_failure, slot0), o.legend, ts);
}

}  // namespace render::internal
