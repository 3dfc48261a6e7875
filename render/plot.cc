// PLplot-based plots (see plot.h). PLplot keeps global state, so each plot runs under one mutex
// in its own stream (plmkstrm ... plend1).
#include "render/plot.h"

#include <plplot.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iterator>
#include <mutex>
#include <stdexcept>
#include <string>

#include "render/internal/text.h"
#include "render/internal/ticks.h"

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

// PLplot colour-map-0 slots: 0 background, 1 ink, 2 grid, 3.. series, then their band colours.
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
  // A little room (2% of the span) so that a line at the data's extremes is not drawn on the frame.
  const double pad = 0.02 * (*hi - *lo);
  *lo -= *lo == 0.0 ? 0.0 : pad;
  *hi += *hi == 0.0 ? 0.0 : pad;
  const double step = std::pow(10.0, std::floor(std::log10(*hi - *lo))) / 2.0;
  *lo = std::floor(*lo / step) * step;
  *hi = std::ceil(*hi / step) * step;
}

}  // namespace

std::array<std::uint8_t, 3> SeriesColor(int i) {
  return kTab10[static_cast<size_t>(((i % 10) + 10) % 10)];
}

namespace {

using Rgb = std::array<std::uint8_t, 3>;

// Data ranges of one set of axes (axis coordinates: log10 on a log y axis).
struct Axes {
  double x_lo, x_hi, y_lo, y_hi, x_pad;
  bool any_failure;
};

void CheckSize(int width, int height, const char* what) {
  if (width < 160 || height < 120) {
    throw std::invalid_argument(std::string(what) + ": figure size " + std::to_string(width) + "x" +
                                std::to_string(height) + " is below the minimum 160x120");
  }
}

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
    if (ps.x.size() != ps.y.size()) {
      throw std::invalid_argument("plot: series " + std::to_string(s) + " ('" + ps.label +
                                  "') has " + std::to_string(ps.x.size()) + " x values but " +
                                  std::to_string(ps.y.size()) + " y values");
    }
    if (ps.y_lo.size() != ps.y_hi.size() || (!ps.y_lo.empty() && ps.y_lo.size() != ps.x.size())) {
      throw std::invalid_argument("plot: series " + std::to_string(s) + " ('" + ps.label +
                                  "'): the band needs y_lo and y_hi with one value per x");
    }
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

// Major tick step of a linear axis over [lo, hi] (about `target` intervals; 1, 2, 2.5, 5 x 10^k)
// and the decimals its labels need.
struct TickStep {
  double step = 0.0;  // 0: let PLplot choose (log axes)
  int decimals = 0;
};
TickStep LinearStep(double lo, double hi, int target) {
  const std::vector<internal::Tick> ticks = internal::NiceTicks(lo, hi, target);
  if (ticks.size() < 2) return {};
  TickStep t;
  t.step = ticks[1].value - ticks[0].value;
  const size_t dot = ticks[1].label.find('.');
  t.decimals = dot == std::string::npos ? 0 : static_cast<int>(ticks[1].label.size() - dot - 1);
  return t;
}

// Tick labels of one panel: fixed decimals per linear axis, 10^k on a log axis, U+2212 minus.
struct LabelFormat {
  TickStep x, y;
  bool log_y = false;
};
void FormatTickLabel(PLINT axis, PLFLT value, char* label, PLINT length, PLPointer data) {
  const auto* f = static_cast<const LabelFormat*>(data);
  std::string text;
  if (axis == PL_Y_AXIS && f->log_y) {
    text = "10#u" + FormatNumber(value, 0) + "#d";
  } else {
    const TickStep& t = axis == PL_X_AXIS ? f->x : f->y;
    text =
        FormatNumber(std::abs(value) < 1e-9 * std::max(t.step, 1e-300) ? 0.0 : value, t.decimals);
  }
  std::snprintf(label, static_cast<size_t>(length), "%s", text.c_str());
}

// Text height (pixels) and PLplot character scale. PLplot sizes characters in proportion to the
// page's width + height, so the scale is computed from the 4:3 page of the same width + height
// (h_eq); the text grows slowly with the size of one set of axes `ref_w` x `ref_h` (about 11 px
// at 640x480, 9 px at 320x240).
struct TextScale {
  double scale, px;
};
TextScale TextScaleFor(int width, int height, double ref_w, double ref_h) {
  const double h_eq = 3.0 * (width + height) / 7.0, ref_eq = 3.0 * (ref_w + ref_h) / 7.0;
  const double px = 11.0 * std::pow(ref_eq / 480.0, 0.3);
  return {0.9 * px * 480.0 / (11.0 * h_eq), px};
}
TextScale TextScaleFor(int width, int height) { return TextScaleFor(width, height, width, height); }

// Viewport of a panel in normalised page coordinates.
struct Box {
  double x0, x1, y0, y1;
};

// Legend entries of a panel, drawn with pllegend.
struct LegendEntries {
  std::vector<PLINT> opts, line_colors, symbol_colors, box_colors;
  std::vector<const char*> texts, symbols;
};

void DrawLegend(const LegendEntries& e, LegendPosition where, const TextScale& ts) {
  if (e.opts.empty() || where == LegendPosition::kNone) return;
  const size_t n = e.opts.size();
  std::vector<PLINT> text_colors(n, kInkSlot), line_styles(n, 1), symbol_numbers(n, 1),
      box_patterns(n, 0);
  std::vector<PLFLT> line_widths(n, 2.0), symbol_scales(n, ts.scale / 0.9), box_scales(n, 0.8),
      box_line_widths(n, 1.0);
  PLINT position = 0;
  if (where == LegendPosition::kOutsideRight) {
    position = PL_POSITION_OUTSIDE | PL_POSITION_RIGHT;
  } else {
    position = PL_POSITION_INSIDE;
    position |= (where == LegendPosition::kTopLeft || where == LegendPosition::kTopRight)
                    ? PL_POSITION_TOP
                    : PL_POSITION_BOTTOM;
    position |= (where == LegendPosition::kTopLeft || where == LegendPosition::kBottomLeft)
                    ? PL_POSITION_LEFT
                    : PL_POSITION_RIGHT;
  }
  PLFLT legend_w = 0, legend_h = 0;
  pllegend(&legend_w, &legend_h, PL_LEGEND_BACKGROUND | PL_LEGEND_BOUNDING_BOX, position, 0.02,
           0.02, 0.08, 0, kInkSlot, 1, 0, 0, static_cast<PLINT>(n), e.opts.data(), 1.0,
           0.95 * ts.scale, 2.0, 0.0, text_colors.data(), e.texts.data(), e.box_colors.data(),
           box_patterns.data(), box_scales.data(), box_line_widths.data(), e.line_colors.data(),
           line_styles.data(), line_widths.data(), e.symbol_colors.data(), symbol_scales.data(),
           symbol_numbers.data(), e.symbols.data());
}

// Room (normalised page width) a legend outside on the right needs when the axes would otherwise
// span `span` (normalised page width). pllegend places it 0.02 viewport widths right of the axes
// and gives its symbols 0.08 viewport widths, so with the viewport span − room wide the room r
// solves r = 0.10·(span − r) + text + margins.
double OutsideLegendWidth(const std::vector<std::string>& labels, const TextScale& ts, int width,
                          double span) {
  float widest = 0.0f;
  for (const std::string& l : labels) {
    widest = std::max(widest, internal::Font::Regular().Width(l, static_cast<float>(1.3 * ts.px)));
  }
  const double text = (widest + 5.0 * ts.px) / width;
  return (0.10 * span + text) / 1.10;
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

// One panel of line/marker series; colour slots slot0.. (lines) and band_slot0.. (bands).
void DrawSeriesPanel(const std::vector<PlotSeries>& series, const PlotOptions& o, const Box& vp,
                     const TextScale& ts, int width, int height, int slot0, int band_slot0) {
  const Axes a = ComputeAxes(series, o);
  LabelFormat labels;
  DrawAxes(o, a, vp, ts, width, height, true, &labels);
  const int n_series = static_cast<int>(series.size());
  // Bands first (under the lines), broken at non-finite ends.
  for (int s = 0; s < n_series; ++s) {
    const PlotSeries& ps = series[static_cast<size_t>(s)];
    if (ps.y_lo.empty()) continue;
    plcol0(band_slot0 + s);
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
      const double l = AxisY(ps.y_lo[k], o.log_y), h = AxisY(ps.y_hi[k], o.log_y);
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
  // Lines broken at unplottable points, then markers, then failures.
  std::vector<double> xs, ys;
  const double top = a.y_hi - 0.03 * (a.y_hi - a.y_lo);
  for (int s = 0; s < n_series; ++s) {
    const PlotSeries& ps = series[static_cast<size_t>(s)];
    plcol0(slot0 + s);
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
      plschr(0.0, 1.3 * ts.scale);
      plstring(1, &fx, &fy, kFailureGlyph);
      plschr(0.0, ts.scale);
    }
  }
  // Legend: one entry per labelled series, plus "failed" when any failures are drawn.
  LegendEntries e;
  for (int s = 0; s < n_series; ++s) {
    const PlotSeries& ps = series[static_cast<size_t>(s)];
    if (ps.label.empty()) continue;
    PLINT opt = 0;
    if (ps.line) opt |= PL_LEGEND_LINE;
    if (ps.marker != Marker::kNone) opt |= PL_LEGEND_SYMBOL;
    e.opts.push_back(opt == 0 ? PL_LEGEND_NONE : opt);
    e.texts.push_back(ps.label.c_str());
    e.symbols.push_back(MarkerGlyph(ps.marker));
    e.line_colors.push_back(slot0 + s);
    e.symbol_colors.push_back(slot0 + s);
    e.box_colors.push_back(slot0 + s);
  }
  if (a.any_failure) {
    e.opts.push_back(PL_LEGEND_SYMBOL);
    e.texts.push_back("Failed run");
    e.symbols.push_back(kFailureGlyph);
    e.line_colors.push_back(kInkSlot);
    e.symbol_colors.push_back(kInkSlot);
    e.box_colors.push_back(kInkSlot);
  }
  DrawLegend(e, o.legend, ts);
}

std::vector<Rgb> ColorsOf(const std::vector<PlotSeries>& series) {
  std::vector<Rgb> colors;
  for (size_t s = 0; s < series.size(); ++s) {
    const auto& c = series[s].rgba;
    colors.push_back(c[3] == 0 ? SeriesColor(static_cast<int>(s)) : Rgb{c[0], c[1], c[2]});
  }
  return colors;
}

// Runs `draw` in a fresh PLplot stream on the device of `format`, with colour slots 3.. set to
// `colors` and the next ones to the same colours at 25% opacity (bands). PNG: returns the
// pixels in *image; SVG/PDF: the file bytes in *bytes.
void RunPlplot(int width, int height, FigureFormat format, const std::vector<Rgb>& colors,
               const std::function<void()>& draw, Image* image, std::string* bytes) {
  static std::atomic<int> counter{0};
  const std::string tmp = (std::filesystem::temp_directory_path() /
                           ("topoplan-plot-" + std::to_string(getpid()) + "-" +
                            std::to_string(counter++) + "." + FigureFormatName(format)))
                              .string();
  std::lock_guard<std::mutex> lock(PlplotMutex());
  PLINT previous = 0, stream = 0;
  plgstrm(&previous);
  plmkstrm(&stream);
  if (format == FigureFormat::kPng) {
    *image = Image(width, height, 255, 255, 255, 255);
    plsdev("memcairo");
    plsmema(width, height, image->rgba.data());
  } else {
    plsdev(format == FigureFormat::kSvg ? "svgcairo" : "pdfcairo");
    plsfnam(tmp.c_str());
    plspage(72.0, 72.0, width, height, 0, 0);
  }
  plscolbg(255, 255, 255);
  const int n = static_cast<int>(colors.size());
  plscmap0n(kFirstSeriesSlot + 2 * std::max(n, 1));
  plscol0(0, 255, 255, 255);
  plscol0(kInkSlot, 0, 0, 0);
  plscol0(kGridSlot, 215, 215, 215);
  for (int s = 0; s < n; ++s) {
    const Rgb& c = colors[static_cast<size_t>(s)];
    plscol0(kFirstSeriesSlot + s, c[0], c[1], c[2]);
    plscol0a(kFirstSeriesSlot + n + s, c[0], c[1], c[2], 0.25);
  }
  plinit();
  pladv(0);
  try {
    draw();
  } catch (...) {
    plend1();
    plsstrm(previous);
    std::filesystem::remove(tmp);
    throw;
  }
  plend1();
  plsstrm(previous);
  if (format == FigureFormat::kPng) {
    for (size_t i = 3; i < image->rgba.size(); i += 4) image->rgba[i] = 255;
    return;
  }
  std::ifstream in(tmp, std::ios::binary);
  if (!in)
    throw std::runtime_error("plot: PLplot wrote no " + std::string(FigureFormatName(format)));
  bytes->assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
  in.close();
  std::filesystem::remove(tmp);
}

// The single-panel plot in `format`.
void DrawPlot(const std::vector<PlotSeries>& series, const PlotOptions& o, FigureFormat format,
              Image* image, std::string* bytes) {
  CheckSize(o.width, o.height, "plot");
  ComputeAxes(series, o);  // throws before PLplot starts
  const std::vector<Rgb> colors = ColorsOf(series);
  const int n = static_cast<int>(series.size());
  RunPlplot(
      o.width, o.height, format, colors,
      [&] {
        const TextScale ts = TextScaleFor(o.width, o.height);
        plschr(0.0, ts.scale);
        double right = 1.0 - 1.6 * ts.px / o.width;
        const double left = 6.4 * ts.px / o.width;
        if (o.legend == LegendPosition::kOutsideRight) {
          std::vector<std::string> labels;
          for (const PlotSeries& s : series) labels.push_back(s.label);
          right -= OutsideLegendWidth(labels, ts, o.width, right - left);
        }
        const Box vp{left, right, 4.6 * ts.px / o.height,
                     1.0 - (o.title.empty() ? 1.2 : 2.6) * ts.px / o.height};
        DrawSeriesPanel(series, o, vp, ts, o.width, o.height, kFirstSeriesSlot,
                        kFirstSeriesSlot + n);
      },
      image, bytes);
}

}  // namespace

Image RenderPlot(const std::vector<PlotSeries>& series, const PlotOptions& o) {
  Image image;
  DrawPlot(series, o, FigureFormat::kPng, &image, nullptr);
  return image;
}

namespace {

void DrawPanels(const std::vector<PlotPanel>& panels, const PanelLayout& L, FigureFormat format,
                Image* image, std::string* bytes) {
  CheckSize(L.width, L.height, "plot");
  if (panels.empty()) throw std::invalid_argument("plot: no panel to draw");
  std::vector<Rgb> colors;
  std::vector<int> first;  // first colour slot offset of each panel
  for (const PlotPanel& p : panels) {
    ComputeAxes(p.series, p.axes);  // throws before PLplot starts
    first.push_back(static_cast<int>(colors.size()));
    for (const Rgb& c : ColorsOf(p.series)) colors.push_back(c);
  }
  const int n = static_cast<int>(colors.size());
  const int columns = std::clamp(L.columns, 1, static_cast<int>(panels.size()));
  const int rows = (static_cast<int>(panels.size()) + columns - 1) / columns;
  RunPlplot(
      L.width, L.height, format, colors,
      [&] {
        const TextScale ts = TextScaleFor(L.width, L.height, static_cast<double>(L.width) / columns,
                                          static_cast<double>(L.height) / rows);
        plschr(0.0, ts.scale);
        const double title_h = L.title.empty() ? 0.0 : 2.2 * ts.px / L.height;
        if (!L.title.empty()) {
          plvpor(0.0, 1.0, 0.0, 1.0);
          plwind(0.0, 1.0, 0.0, 1.0);
          plcol0(kInkSlot);
          plschr(0.0, 1.25 * ts.scale);
          plptex(0.5, 1.0 - 0.6 * title_h, 1.0, 0.0, 0.5, L.title.c_str());
          plschr(0.0, ts.scale);
        }
        const double cell_w = 1.0 / columns, cell_h = (1.0 - title_h) / rows;
        for (size_t k = 0; k < panels.size(); ++k) {
          const PlotOptions& o = panels[k].axes;
          const int r = static_cast<int>(k) / columns, c = static_cast<int>(k) % columns;
          const double x0 = c * cell_w, y1 = 1.0 - title_h - r * cell_h;
          double right = x0 + cell_w - 1.6 * ts.px / L.width;
          if (o.legend == LegendPosition::kOutsideRight) {
            std::vector<std::string> labels;
            for (const PlotSeries& s : panels[k].series) labels.push_back(s.label);
            right -= OutsideLegendWidth(labels, ts, L.width, right - x0 - 6.4 * ts.px / L.width);
          }
          const Box vp{x0 + 6.4 * ts.px / L.width, right, y1 - cell_h + 4.6 * ts.px / L.height,
                       y1 - (o.title.empty() ? 1.2 : 2.6) * ts.px / L.height};
          DrawSeriesPanel(panels[k].series, o, vp, ts, L.width, L.height,
                          kFirstSeriesSlot + first[k], kFirstSeriesSlot + n + first[k]);
        }
      },
      image, bytes);
}

void DrawBars(const BarChart& chart, const PlotOptions& o, FigureFormat format, Image* image,
              std::string* bytes) {
  CheckSize(o.width, o.height, "bar chart");
  const size_t nc = chart.categories.size(), ns = chart.series.size();
  if (nc == 0) throw std::invalid_argument("bar chart: no category");
  double top = 0.0;
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
      if (std::isfinite(v)) top = std::max(top, v);
    }
    for (double v : b.hi) {
      if (std::isfinite(v)) top = std::max(top, v);
    }
    colors.push_back(b.rgba[3] == 0 ? SeriesColor(static_cast<int>(s))
                                    : Rgb{b.rgba[0], b.rgba[1], b.rgba[2]});
  }
  double y_lo = std::isfinite(o.y_min) ? o.y_min : 0.0;
  double y_hi = std::isfinite(o.y_max) ? o.y_max : top;
  if (!std::isfinite(o.y_max)) NiceRange(&y_lo, &y_hi);
  if (!(y_hi > y_lo)) y_hi = y_lo + 1.0;
  RunPlplot(
      o.width, o.height, format, colors,
      [&] {
        const TextScale ts = TextScaleFor(o.width, o.height);
        plschr(0.0, ts.scale);
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
          right -= OutsideLegendWidth(labels, ts, o.width, right - left);
        }
        const bool upright = widest > 0.9 * (right - left) * o.width / static_cast<double>(nc);
        const double label_h = upright ? widest + 1.5 * ts.px : 1.6 * ts.px;
        const Box vp{left, right, (label_h + 3.4 * ts.px) / o.height,
                     1.0 - (o.title.empty() ? 1.2 : 2.6) * ts.px / o.height};
        plvpor(vp.x0, vp.x1, vp.y0, vp.y1);
        // 4% headroom: bars and whiskers at the top value stay clear of the frame.
        plwind(0.5, nc + 0.5, y_lo, y_hi + 0.04 * (y_hi - y_lo));
        LabelFormat labels;
        labels.y = LinearStep(
            y_lo, y_hi, std::max(2, static_cast<int>((vp.y1 - vp.y0) * o.height / (4.0 * ts.px))));
        plslabelfunc(FormatTickLabel, &labels);
        plcol0(kGridSlot);
        plwidth(0.6);
        plbox("", 0.0, 0, "g", labels.y.step, 0);
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
        plcol0(kInkSlot);
        plwidth(1.0);
        plbox("bc", 0.0, 0, "bcnstvo", labels.y.step, 0);
        for (size_t c = 0; c < nc; ++c) {
          const double pos = (static_cast<double>(c) + 0.5) / nc;
          if (upright) {
            plmtex("bv", 0.6, pos, 1.0, chart.categories[c].c_str());
          } else {
            plmtex("b", 1.5, pos, 0.5, chart.categories[c].c_str());
          }
        }
        plmtex("b", (label_h + 1.6 * ts.px) / (ts.px * 1.0) * 0.75, 0.5, 0.5, o.x_label.c_str());
        plmtex("l", 3.6, 0.5, 0.5, o.y_label.c_str());
        if (!o.title.empty()) {
          plschr(0.0, 1.2 * ts.scale);
          plmtex("t", 1.2, 0.5, 0.5, o.title.c_str());
          plschr(0.0, ts.scale);
        }
        LegendEntries e;
        for (size_t s = 0; s < ns; ++s) {
          e.opts.push_back(PL_LEGEND_COLOR_BOX);
          e.texts.push_back(chart.series[s].label.c_str());
          e.symbols.push_back("");
          e.line_colors.push_back(kInkSlot);
          e.symbol_colors.push_back(kInkSlot);
          e.box_colors.push_back(kFirstSeriesSlot + static_cast<int>(s));
        }
        DrawLegend(e, o.legend, ts);
      },
      image, bytes);
}

}  // namespace

namespace {

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

}  // namespace

Figure PlotFigure(const std::vector<PlotSeries>& series, const PlotOptions& options) {
  return PlplotFigure([series, options](FigureFormat f, Image* image, std::string* bytes) {
    DrawPlot(series, options, f, image, bytes);
  });
}

Figure PanelsFigure(const std::vector<PlotPanel>& panels, const PanelLayout& layout) {
  return PlplotFigure([panels, layout](FigureFormat f, Image* image, std::string* bytes) {
    DrawPanels(panels, layout, f, image, bytes);
  });
}

Figure BarChartFigure(const BarChart& chart, const PlotOptions& options) {
  return PlplotFigure([chart, options](FigureFormat f, Image* image, std::string* bytes) {
    DrawBars(chart, options, f, image, bytes);
  });
}

}  // namespace render
