// PLplot streams, ticks, text scale and legends shared by every plot (see plplot_figure.h).
// PLplot keeps global state, so each figure runs under one mutex in its own stream
// (plmkstrm ... plend1).
#include "render/internal/plplot_figure.h"

#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <mutex>
#include <stdexcept>

#include "render/internal/text.h"
#include "render/internal/ticks.h"

namespace render::internal {
namespace {

std::mutex& PlplotMutex() {
  static std::mutex m;
  return m;
}

}  // namespace

void CheckFigureSize(int width, int height, const char* what) {
  if (width < 160 || height < 120) {
    throw std::invalid_argument(std::string(what) + ": figure size " + std::to_string(width) + "x" +
                                std::to_string(height) + " is below the minimum 160x120");
  }
}

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

TickStep LinearStep(double lo, double hi, int target) {
  const std::vector<Tick> ticks = NiceTicks(lo, hi, target);
  if (ticks.size() < 2) return {};
  TickStep t;
  t.step = ticks[1].value - ticks[0].value;
  const size_t dot = ticks[1].label.find('.');
  t.decimals = dot == std::string::npos ? 0 : static_cast<int>(ticks[1].label.size() - dot - 1);
  return t;
}

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

TextScale TextScaleFor(int width, int height, double ref_w, double ref_h) {
  const double h_eq = 3.0 * (width + height) / 7.0, ref_eq = 3.0 * (ref_w + ref_h) / 7.0;
  const double px = 11.0 * std::pow(ref_eq / 480.0, 0.3);
  return {0.9 * px * 480.0 / (11.0 * h_eq), px};
}
TextScale TextScaleFor(int width, int height) { return TextScaleFor(width, height, width, height); }

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

double OutsideLegendWidth(const std::vector<std::string>& labels, const TextScale& ts, int width,
                          double span) {
  float widest = 0.0f;
  for (const std::string& l : labels) {
    widest = std::max(widest, Font::Regular().Width(l, static_cast<float>(1.3 * ts.px)));
  }
  const double text = (widest + 5.0 * ts.px) / width;
  return (0.10 * span + text) / 1.10;
}

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

}  // namespace render::internal
