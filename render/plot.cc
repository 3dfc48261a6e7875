// PLplot-based plots (see plot.h). PLplot keeps global state, so each plot runs under one mutex
// in its own stream (plmkstrm ... plend1).
#include "render/plot.h"

#include <plplot.h>

#include <algorithm>
#include <cmath>
#include <mutex>
#include <stdexcept>
#include <string>

namespace render {
namespace {

constexpr std::array<std::array<std::uint8_t, 3>, 10> kTab10 = {{{31, 119, 180},
                                                                 {255, 127, 14},
                                                                 {44, 160, 44},
                                                                 {214, 39, 40},
                                                                 {148, 103, 189},
                                                                 {140, 86, 75},
                                                                 {227, 119, 194},
                                                                 {127, 127, 127},
                                                                 {188, 189, 34},
                                                                 {23, 190, 207}}};

// PLplot colour-map-0 slots: 0 background, 1 ink, 2 grid, 3.. series.
constexpr int kInkSlot = 1, kGridSlot = 2, kFirstSeriesSlot = 3;

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

std::mutex& PlplotMutex() {
  static std::mutex m;
  return m;
}

// Value as plotted on the y axis (log10 on a log axis; NaN when not plottable).
double AxisY(double y, bool log_y) {
  if (!std::isfinite(y)) return std::numeric_limits<double>::quiet_NaN();
  if (!log_y) return y;
  return y > 0.0 ? std::log10(y) : std::numeric_limits<double>::quiet_NaN();
}

// Nice linear range containing [lo, hi].
void NiceRange(double* lo, double* hi) {
  if (*hi <= *lo) {
    const double pad = *lo == 0.0 ? 1.0 : 0.1 * std::abs(*lo);
    *lo -= pad;
    *hi += pad;
    return;
  }
  const double step = std::pow(10.0, std::floor(std::log10(*hi - *lo))) / 2.0;
  *lo = std::floor(*lo / step) * step;
  *hi = std::ceil(*hi / step) * step;
}

}  // namespace

std::array<std::uint8_t, 3> SeriesColor(int i) {
  return kTab10[static_cast<size_t>(((i % 10) + 10) % 10)];
}

Image RenderPlot(const std::vector<PlotSeries>& series, const PlotOptions& o) {
  if (o.width < 160 || o.height < 120) {
    throw std::invalid_argument("plot: figure size " + std::to_string(o.width) + "x" +
                                std::to_string(o.height) + " is below the minimum 160x120");
  }
  // Data ranges in axis coordinates.
  double x_lo = std::numeric_limits<double>::infinity(), x_hi = -x_lo;
  double y_lo = x_lo, y_hi = -x_lo;
  bool any_failure = false;
  for (size_t s = 0; s < series.size(); ++s) {
    const PlotSeries& ps = series[s];
    if (ps.x.size() != ps.y.size()) {
      throw std::invalid_argument("plot: series " + std::to_string(s) + " ('" + ps.label +
                                  "') has " + std::to_string(ps.x.size()) + " x values but " +
                                  std::to_string(ps.y.size()) + " y values");
    }
    for (size_t k = 0; k < ps.x.size(); ++k) {
      const double ay = AxisY(ps.y[k], o.log_y);
      if (!std::isfinite(ps.x[k]) || !std::isfinite(ay)) continue;
      x_lo = std::min(x_lo, ps.x[k]);
      x_hi = std::max(x_hi, ps.x[k]);
      y_lo = std::min(y_lo, ay);
      y_hi = std::max(y_hi, ay);
    }
    for (size_t k = 0; k < ps.failure_x.size(); ++k) {
      any_failure = true;
      if (std::isfinite(ps.failure_x[k])) {
        x_lo = std::min(x_lo, ps.failure_x[k]);
        x_hi = std::max(x_hi, ps.failure_x[k]);
      }
      if (ps.failure_y.size() == ps.failure_x.size()) {
        const double ay = AxisY(ps.failure_y[k], o.log_y);
        if (std::isfinite(ay)) {
          y_lo = std::min(y_lo, ay);
          y_hi = std::max(y_hi, ay);
        }
      }
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

  Image img(o.width, o.height, 255, 255, 255, 255);
  std::lock_guard<std::mutex> lock(PlplotMutex());
  PLINT previous = 0, stream = 0;
  plgstrm(&previous);
  plmkstrm(&stream);
  plsdev("memcairo");
  plsmema(o.width, o.height, img.rgba.data());
  plscolbg(255, 255, 255);
  plscol0(0, 255, 255, 255);
  plscol0(kInkSlot, 0, 0, 0);
  plscol0(kGridSlot, 215, 215, 215);
  const int n_series = static_cast<int>(series.size());
  std::vector<std::array<std::uint8_t, 3>> colors(series.size());
  for (int s = 0; s < n_series; ++s) {
    const auto& c = series[static_cast<size_t>(s)].rgba;
    colors[static_cast<size_t>(s)] = c[3] == 0 ? SeriesColor(s) : std::array{c[0], c[1], c[2]};
  }
  plscmap0n(kFirstSeriesSlot + std::max(n_series, 1));
  plscol0(0, 255, 255, 255);
  plscol0(kInkSlot, 0, 0, 0);
  plscol0(kGridSlot, 215, 215, 215);
  for (int s = 0; s < n_series; ++s) {
    const auto& c = colors[static_cast<size_t>(s)];
    plscol0(kFirstSeriesSlot + s, c[0], c[1], c[2]);
  }
  plinit();
  pladv(0);
  // PLplot sizes text relative to the page; grow it on small figures so that it stays readable
  // (about 11 px at 640x480, 9 px at 320x240), and size the margins in text heights.
  const double text_scale = 0.9 * std::pow(480.0 / o.height, 0.7);
  const double text_px = 11.0 * (text_scale / 0.9) * o.height / 480.0;
  plschr(0.0, text_scale);
  plvpor(6.4 * text_px / o.width, 1.0 - 1.6 * text_px / o.width, 4.6 * text_px / o.height,
         1.0 - (o.title.empty() ? 1.2 : 2.6) * text_px / o.height);
  plwind(x_lo - x_pad, x_hi + x_pad, y_lo, y_hi);
  plcol0(kGridSlot);
  plwidth(0.6);
  plbox("g", 0.0, 0, o.log_y ? "gl" : "g", 0.0, 0);
  plcol0(kInkSlot);
  plwidth(1.0);
  plbox("bcnst", 0.0, 0, o.log_y ? "bcnstlv" : "bcnstv", 0.0, 0);
  pllab(o.x_label.c_str(), o.y_label.c_str(), "");
  if (!o.title.empty()) {  // the title a little larger than the labels
    plschr(0.0, 1.2 * text_scale);
    plmtex("t", 1.2, 0.5, 0.5, o.title.c_str());
    plschr(0.0, text_scale);
  }

  // Series: lines broken at unplottable points, then markers, then failures.
  std::vector<double> xs, ys;
  const double top = y_hi - 0.03 * (y_hi - y_lo);
  for (int s = 0; s < n_series; ++s) {
    const PlotSeries& ps = series[static_cast<size_t>(s)];
    plcol0(kFirstSeriesSlot + s);
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
      const double ay = AxisY(ps.y[k], o.log_y);
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
        const double ay = AxisY(ps.failure_y[k], o.log_y);
        if (std::isfinite(ay)) fy = ay;
      }
      const double fx = ps.failure_x[k];
      plschr(0.0, 1.3 * text_scale);
      plstring(1, &fx, &fy, kFailureGlyph);
      plschr(0.0, text_scale);
    }
  }

  // Legend: one entry per labelled series, plus "failed" when any failures are drawn.
  std::vector<PLINT> opts, text_colors, line_colors, line_styles, symbol_colors, symbol_numbers;
  std::vector<PLFLT> line_widths, symbol_scales;
  std::vector<const char*> texts, symbols;
  for (int s = 0; s < n_series; ++s) {
    const PlotSeries& ps = series[static_cast<size_t>(s)];
    if (ps.label.empty()) continue;
    PLINT opt = 0;
    if (ps.line) opt |= PL_LEGEND_LINE;
    if (ps.marker != Marker::kNone) opt |= PL_LEGEND_SYMBOL;
    opts.push_back(opt == 0 ? PL_LEGEND_NONE : opt);
    texts.push_back(ps.label.c_str());
    symbols.push_back(MarkerGlyph(ps.marker));
    line_colors.push_back(kFirstSeriesSlot + s);
    symbol_colors.push_back(kFirstSeriesSlot + s);
  }
  if (any_failure) {
    opts.push_back(PL_LEGEND_SYMBOL);
    texts.push_back("failed");
    symbols.push_back(kFailureGlyph);
    line_colors.push_back(kInkSlot);
    symbol_colors.push_back(kInkSlot);
  }
  if (!opts.empty() && o.legend != LegendPosition::kNone) {
    const size_t n = opts.size();
    text_colors.assign(n, kInkSlot);
    line_styles.assign(n, 1);
    line_widths.assign(n, 2.0);
    symbol_scales.assign(n, text_scale / 0.9);
    symbol_numbers.assign(n, 1);
    PLINT position = PL_POSITION_INSIDE;
    position |= (o.legend == LegendPosition::kTopLeft || o.legend == LegendPosition::kTopRight)
                    ? PL_POSITION_TOP
                    : PL_POSITION_BOTTOM;
    position |= (o.legend == LegendPosition::kTopLeft || o.legend == LegendPosition::kBottomLeft)
                    ? PL_POSITION_LEFT
                    : PL_POSITION_RIGHT;
    PLFLT legend_w = 0, legend_h = 0;
    pllegend(&legend_w, &legend_h, PL_LEGEND_BACKGROUND | PL_LEGEND_BOUNDING_BOX, position, 0.02,
             0.02, 0.08, 0, kInkSlot, 1, 0, 0, static_cast<PLINT>(n), opts.data(), 1.0,
             0.95 * text_scale, 2.0, 0.0, text_colors.data(), texts.data(), nullptr, nullptr,
             nullptr, nullptr, line_colors.data(), line_styles.data(), line_widths.data(),
             symbol_colors.data(), symbol_scales.data(), symbol_numbers.data(), symbols.data());
  }
  plend1();
  plsstrm(previous);
  for (size_t i = 3; i < img.rgba.size(); i += 4) img.rgba[i] = 255;
  return img;
}

}  // namespace render
