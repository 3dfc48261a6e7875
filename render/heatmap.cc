// Heatmap figures and colormaps (see heatmap.h).
#include "render/heatmap.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <string>
#include <vector>

#include "render/internal/canvas.h"
#include "render/internal/painter.h"
#include "render/internal/text.h"
#include "render/internal/ticks.h"

namespace render {
namespace {

using internal::Align;
using internal::Font;
using internal::Rgb;

constexpr Rgb kInk{30, 30, 30};
constexpr Rgb kFrame{60, 60, 60};
constexpr Rgb kNanGrey{180, 180, 180};
constexpr int kTickLen = 4;

// Text sizes scale with the figure (1 at 640x480), within [0.8, 1.6].
struct TextSizes {
  float title, label, tick;
};
TextSizes SizesFor(int width, int height) {
  const float s = std::clamp(std::min(width / 640.0f, height / 480.0f), 0.8f, 1.6f);
  return {std::round(16.0f * s), std::round(13.0f * s), std::round(11.0f * s)};
}

// ColorBrewer RdBu (11 classes), from the negative end (blue) to the positive end (red).
constexpr std::array<Rgb, 11> kRdBu = {{{5, 48, 97},
                                        {33, 102, 172},
                                        {67, 147, 195},
                                        {146, 197, 222},
                                        {209, 229, 240},
                                        {247, 247, 247},
                                        {253, 219, 199},
                                        {244, 165, 130},
                                        {214, 96, 77},
                                        {178, 24, 43},
                                        {103, 0, 31}}};
// matplotlib viridis at t = 0, 1/8, ..., 1.
constexpr std::array<Rgb, 9> kViridis = {{{68, 1, 84},
                                          {71, 45, 123},
                                          {59, 82, 139},
                                          {44, 114, 142},
                                          {33, 145, 140},
                                          {40, 174, 128},
                                          {94, 201, 98},
                                          {173, 220, 48},
                                          {253, 231, 37}}};

template <size_t N>
Rgb Interpolate(const std::array<Rgb, N>& table, double s) {
  s = std::clamp(s, 0.0, 1.0) * static_cast<double>(N - 1);
  const size_t i = std::min(static_cast<size_t>(s), N - 2);
  const double f = s - static_cast<double>(i);
  Rgb out;
  for (int c = 0; c < 3; ++c) {
    out[c] = static_cast<std::uint8_t>(std::lround((1.0 - f) * table[i][c] + f * table[i + 1][c]));
  }
  return out;
}

}  // namespace

std::array<std::uint8_t, 3> DivergingColor(double t) {
  if (!std::isfinite(t)) return kNanGrey;
  return Interpolate(kRdBu, 0.5 * (std::clamp(t, -1.0, 1.0) + 1.0));
}

std::array<std::uint8_t, 3> ViridisColor(double t) {
  if (!std::isfinite(t)) return kNanGrey;
  return Interpolate(kViridis, t);
}

double SequenceLimit(const std::vector<Eigen::MatrixXd>& matrices) {
  double max_abs = 0.0;
  for (const Eigen::MatrixXd& m : matrices) {
    for (Eigen::Index i = 0; i < m.size(); ++i) {
      if (std::isfinite(m.data()[i])) max_abs = std::max(max_abs, std::abs(m.data()[i]));
    }
  }
  return max_abs > 0.0 ? max_abs : 1.0;
}

namespace {

// Margins around the matrix (pixels) for a figure of text sizes `sz`.
struct Margins {
  int top, bottom, left, bar_block;
};
Margins MarginsFor(int rows, const HeatmapOptions& o, const TextSizes& sz) {
  const Font& font = Font::Regular();
  Margins m;
  m.top = o.title.empty() ? 12 : static_cast<int>(std::ceil(sz.title * 1.2f)) + 16;
  m.bottom = static_cast<int>(sz.tick + sz.label) + kTickLen + 18 +
             (o.mark_peak ? static_cast<int>(std::ceil(sz.tick * 1.5f)) : 0);
  const float widest_row = font.Width(std::to_string((rows - 1) * o.row_block), sz.tick);
  m.left = static_cast<int>(std::ceil(widest_row)) + kTickLen + 10 + static_cast<int>(sz.label) + 8;
  m.bar_block = 14 + 14 + kTickLen + 4 + static_cast<int>(font.Width("\u22120.0000", sz.tick)) + 8 +
                static_cast<int>(sz.label) + 6;
  return m;
}

}  // namespace

HeatmapLayout ComputeHeatmapLayout(int rows, int cols, const HeatmapOptions& o) {
  if (rows < 1 || cols < 1) throw std::invalid_argument("heatmap: empty matrix");
  if (o.width < 160 || o.height < 120) {
    throw std::invalid_argument("heatmap: figure size " + std::to_string(o.width) + "x" +
                                std::to_string(o.height) + " is below the minimum 160x120");
  }
  const TextSizes sz = SizesFor(o.width, o.height);
  const Margins m = MarginsFor(rows, o, sz);
  const int avail_w = std::max(1, o.width - m.left - m.bar_block - 6);
  const int avail_h = std::max(1, o.height - m.top - m.bottom);

  HeatmapLayout L;
  auto edges = [](int n, int origin, int span, std::vector<int>* e) {
    e->resize(static_cast<size_t>(n) + 1);
    for (int k = 0; k <= n; ++k) {
      (*e)[static_cast<size_t>(k)] =
          origin + static_cast<int>((static_cast<long>(k) * span + n / 2) / n);
    }
  };
  const int cell_w = avail_w / cols, cell_h = avail_h / rows;
  if (cell_w >= 1 && cell_h >= 1) {
    // Square cells, except that a long thin matrix (20x1 arm against a pole, 3x24 hand against a
    // ring) whose square cells would fill < 40% of one side gets cells up to 4:1 there.
    const int cell = std::min(cell_w, cell_h);
    const int cw = cell * cols < avail_w * 2 / 5 ? std::min(cell_w, 4 * cell) : cell;
    const int ch = cell * rows < avail_h * 2 / 5 ? std::min(cell_h, 4 * cell) : cell;
    L.plot_w = cw * cols;
    L.plot_h = ch * rows;
  } else {
    L.plot_w = std::min(avail_w, cols * std::max(cell_w, 1));
    L.plot_h = std::min(avail_h, rows * std::max(cell_h, 1));
  }
  // The colour bar keeps a readable height even next to a flat matrix, centred on it.
  L.bar_w = 14;
  L.bar_h = L.plot_h >= 80 ? L.plot_h : std::min(avail_h, 120);
  L.width = o.width;
  L.height = o.height;
  if (o.fit_to_matrix) {  // shrink the canvas to the matrix, the colour bar and the title
    const int title_w =
        o.title.empty() ? 0 : static_cast<int>(std::ceil(Font::Bold().Width(o.title, sz.title)));
    L.width = std::clamp(std::max(m.left + L.plot_w + m.bar_block + 6, title_w + 16), 160, o.width);
    L.height = std::clamp(m.top + std::max(L.plot_h, L.bar_h) + m.bottom, 120, o.height);
  }
  const int free_w = std::max(0, L.width - m.left - m.bar_block - 6 - L.plot_w);
  const int free_h = std::max(0, L.height - m.top - m.bottom - L.plot_h);
  // Centre the whole group (row labels, matrix, colour bar).
  L.plot_x = m.left + free_w / 2;
  L.plot_y = m.top + free_h / 2;
  edges(cols, L.plot_x, L.plot_w, &L.col_edges);
  edges(rows, L.plot_y, L.plot_h, &L.row_edges);
  L.bar_x = L.plot_x + L.plot_w + 14;
  L.bar_y = L.plot_y + (L.plot_h - L.bar_h) / 2;
  return L;
}

namespace {

void DrawHeatmap(const Eigen::MatrixXd& values, const HeatmapOptions& o, const HeatmapLayout& L,
                 internal::Painter* p) {
  const int rows = static_cast<int>(values.rows()), cols = static_cast<int>(values.cols());
  const Font& font = Font::Regular();
  const auto [kTitlePx, kLabelPx, kTickPx] = SizesFor(o.width, o.height);

  // Colour scale and limits.
  double max_abs = 0.0;
  bool any_negative = false;
  Eigen::Index peak = -1;
  for (Eigen::Index i = 0; i < values.size(); ++i) {
    const double v = values.data()[i];
    if (!std::isfinite(v)) continue;
    if (peak < 0 || std::abs(v) > max_abs) peak = i;
    max_abs = std::max(max_abs, std::abs(v));
    any_negative = any_negative || v < 0.0;
  }
  const bool diverging =
      o.scale == ColorScale::kDiverging || (o.scale == ColorScale::kAuto && any_negative);
  const double limit = o.limit > 0.0 ? o.limit : (max_abs > 0.0 ? max_abs : 1.0);
  auto color_of = [&](double v) {
    return diverging ? DivergingColor(v / limit) : ViridisColor(v / limit);
  };

  // Cells, row-major.
  for (int i = 0; i < rows; ++i) {
    for (int j = 0; j < cols; ++j) {
      p->Fill(L.col_edges[j], L.row_edges[i], L.col_edges[j + 1], L.row_edges[i + 1],
              color_of(values(i, j)), "cell");
    }
  }
  p->Stroke(L.plot_x - 1, L.plot_y - 1, L.plot_x + L.plot_w + 1, L.plot_y + L.plot_h + 1, kFrame);

  // Index ticks: a step of 1, 2, 5, 10, ... so that labels do not crowd.
  auto index_step = [&](int n, int span, float label_px) {
    const double min_gap = label_px + 8.0;
    for (int step : {1, 2, 5, 10, 20, 25, 50, 100, 200, 250, 500, 1000, 2000, 5000, 10000}) {
      if (static_cast<double>(span) * step / n >= min_gap) return step;
    }
    return std::max(1, n);
  };
  const int col_step = index_step(
      cols, L.plot_w, font.Width(std::to_string((cols - 1) * o.col_block), kTickPx) + 2.0f);
  const int row_step = index_step(rows, L.plot_h, kTickPx);
  const int x_axis_y = L.plot_y + L.plot_h + 1;
  for (int j = 0; j < cols; j += col_step) {
    const int cx = (L.col_edges[j] + L.col_edges[j + 1]) / 2;
    p->Fill(cx, x_axis_y, cx + 1, x_axis_y + kTickLen, kFrame);
    p->Text(static_cast<float>(cx) + 0.5f, x_axis_y + kTickLen + 2 + font.Ascent(kTickPx),
            std::to_string(j * o.col_block), kTickPx, kInk, Align::kCenter);
  }
  const float mid_line = 0.5f * (font.Ascent(kTickPx) - font.Descent(kTickPx));
  for (int i = 0; i < rows; i += row_step) {
    const int cy = (L.row_edges[i] + L.row_edges[i + 1]) / 2;
    p->Fill(L.plot_x - 1 - kTickLen, cy, L.plot_x - 1, cy + 1, kFrame);
    p->Text(static_cast<float>(L.plot_x - kTickLen - 4), static_cast<float>(cy) + 0.5f + mid_line,
            std::to_string(i * o.row_block), kTickPx, kInk, Align::kRight);
  }
  // Axis captions, title and the peak note.
  const float col_label_y = x_axis_y + kTickLen + 2 + kTickPx + 6 + font.Ascent(kLabelPx);
  p->Text(L.plot_x + 0.5f * L.plot_w, col_label_y, o.col_label, kLabelPx, kInk, Align::kCenter);
  const float widest_row = font.Width(std::to_string((rows - 1) * o.row_block), kTickPx);
  p->VerticalText(L.plot_x - kTickLen - 10 - widest_row - 0.5f * kLabelPx,
                  L.plot_y + 0.5f * L.plot_h, o.row_label, kLabelPx, kInk);
  if (!o.title.empty()) {
    p->Text(0.5f * L.width, 8 + Font::Bold().Ascent(kTitlePx), o.title, kTitlePx, kInk,
            Align::kCenter, /*bold=*/true);
  }
  if (o.mark_peak && peak >= 0) {
    const int pi = static_cast<int>(peak % rows), pj = static_cast<int>(peak / rows);
    const int x0 = L.col_edges[pj], x1 = L.col_edges[pj + 1];
    const int y0 = L.row_edges[pi], y1 = L.row_edges[pi + 1];
    p->Stroke(x0 - 1, y0 - 1, x1 + 1, y1 + 1, {255, 255, 255}, 1);
    p->Stroke(x0 - 3, y0 - 3, x1 + 3, y1 + 3, kInk, 2);
    const std::string note = "Peak (outlined): row " + std::to_string(pi * o.row_block) +
                             ", column " + std::to_string(pj * o.col_block) + " (" +
                             FormatNumber(values(pi, pj), 3) + ")";
    p->Text(L.plot_x + 0.5f * L.plot_w,
            col_label_y + font.Descent(kLabelPx) + 4 + font.Ascent(kTickPx), note, kTickPx, kInk,
            Align::kCenter);
  }

  // Colour bar: one colour per pixel row, top = +limit.
  const double lo = diverging ? -limit : 0.0, hi = limit;
  for (int y = 0; y < L.bar_h; ++y) {
    const double v = hi - (hi - lo) * (y + 0.5) / L.bar_h;
    p->Fill(L.bar_x, L.bar_y + y, L.bar_x + L.bar_w, L.bar_y + y + 1, color_of(v), "bar");
  }
  p->Stroke(L.bar_x - 1, L.bar_y - 1, L.bar_x + L.bar_w + 1, L.bar_y + L.bar_h + 1, kFrame);
  float widest_tick = 0.0f;
  for (const internal::Tick& t : internal::NiceTicks(lo, hi, std::max(2, L.bar_h / 40))) {
    const int y =
        L.bar_y + static_cast<int>(std::lround((hi - t.value) / (hi - lo) * (L.bar_h - 1)));
    const int x = L.bar_x + L.bar_w + 1;
    p->Fill(x, y, x + kTickLen, y + 1, kFrame);
    p->Text(static_cast<float>(x + kTickLen + 3), y + 0.5f + mid_line, t.label, kTickPx, kInk,
            Align::kLeft);
    widest_tick = std::max(widest_tick, font.Width(t.label, kTickPx));
  }
  p->VerticalText(L.bar_x + L.bar_w + kTickLen + 3 + widest_tick + 6 + 0.5f * kLabelPx,
                  L.bar_y + 0.5f * L.bar_h, o.value_label, kLabelPx, kInk);
}

}  // namespace

Image RenderHeatmap(const Eigen::MatrixXd& values, const HeatmapOptions& o) {
  const HeatmapLayout L =
      ComputeHeatmapLayout(static_cast<int>(values.rows()), static_cast<int>(values.cols()), o);
  Image img(L.width, L.height, 255, 255, 255);
  DrawHeatmap(values, o, L, internal::MakeRasterPainter(&img).get());
  return img;
}

Figure HeatmapFigure(const Eigen::MatrixXd& values, const HeatmapOptions& options) {
  return Figure([values, options] { return RenderHeatmap(values, options); },
                [values, options](FigureFormat format) {
                  const HeatmapLayout L = ComputeHeatmapLayout(
                      static_cast<int>(values.rows()), static_cast<int>(values.cols()), options);
                  const auto painter = format == FigureFormat::kPdf
                                           ? internal::MakePdfPainter(L.width, L.height)
                                           : internal::MakeSvgPainter(L.width, L.height);
                  DrawHeatmap(values, options, L, painter.get());
                  return painter->Finish();
                });
}

}  // namespace render
