// Line plots and pages of panels (see plot.h): the tab10 series colours, the page layout of a
// single plot or a grid of panels (text scale, margins, room for an outside legend, figure
// title), and their Figures. Each set of axes is drawn by internal/plot_panel.cc in a PLplot
// stream of internal/plplot_figure.cc; bar charts are in plot_bars.cc.
#include "render/plot.h"

#include <algorithm>
#include <stdexcept>
#include <string>

#include "render/internal/plot_panel.h"
#include "render/internal/plplot_figure.h"

namespace render {
namespace {

using internal::Box;
using internal::kFirstSeriesSlot;
using internal::kInkSlot;
using internal::Rgb;
using internal::TextScale;

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

// The single-panel plot in `format`.
void DrawPlot(const std::vector<PlotSeries>& series, const PlotOptions& o, FigureFormat format,
              Image* image, std::string* bytes) {
  internal::CheckFigureSize(o.width, o.height, "plot");
  internal::ComputeAxes(series, o);  // throws before PLplot starts
  const std::vector<Rgb> colors = internal::ColorsOf(series);
  const int n = static_cast<int>(series.size());
  internal::RunPlplot(
      o.width, o.height, format, colors,
      [&] {
        const TextScale ts = internal::TextScaleFor(o.width, o.height);
        plschr(0.0, ts.scale);
        double right = 1.0 - 1.6 * ts.px / o.width;
        const double left = 6.4 * ts.px / o.width;
        if (o.legend == LegendPosition::kOutsideRight) {
          std::vector<std::string> labels;
          for (const PlotSeries& s : series) labels.push_back(s.label);
          right -= internal::OutsideLegendWidth(labels, ts, o.width, right - left);
        }
        const Box vp{left, right, 4.6 * ts.px / o.height,
                     1.0 - (o.title.empty() ? 1.2 : 2.6) * ts.px / o.height};
        internal::DrawSeriesPanel(series, o, vp, ts, o.width, o.height, kFirstSeriesSlot,
                                  kFirstSeriesSlot + n);
      },
      image, bytes);
}

// The figure title centred above the panels, `title_h` (normalised page height) high.
void DrawPageTitle(const std::string& title, double title_h, const TextScale& ts) {
  plvpor(0.0, 1.0, 0.0, 1.0);
  plwind(0.0, 1.0, 0.0, 1.0);
  plcol0(kInkSlot);
  plschr(0.0, 1.25 * ts.scale);
  plptex(0.5, 1.0 - 0.6 * title_h, 1.0, 0.0, 0.5, title.c_str());
  plschr(0.0, ts.scale);
}

void DrawPanels(const std::vector<PlotPanel>& panels, const PanelLayout& L, FigureFormat format,
                Image* image, std::string* bytes) {
  internal::CheckFigureSize(L.width, L.height, "plot");
  if (panels.empty()) throw std::invalid_argument("plot: no panel to draw");
  std::vector<Rgb> colors;
  std::vector<int> first;  // first colour slot offset of each panel
  for (const PlotPanel& p : panels) {
    internal::ComputeAxes(p.series, p.axes);  // throws before PLplot starts
    first.push_back(static_cast<int>(colors.size()));
    for (const Rgb& c : internal::ColorsOf(p.series)) colors.push_back(c);
  }
  const int n = static_cast<int>(colors.size());
  const int columns = std::clamp(L.columns, 1, static_cast<int>(panels.size()));
  const int rows = (static_cast<int>(panels.size()) + columns - 1) / columns;
  internal::RunPlplot(
      L.width, L.height, format, colors,
      [&] {
        const TextScale ts =
            internal::TextScaleFor(L.width, L.height, static_cast<double>(L.width) / columns,
                                   static_cast<double>(L.height) / rows);
        plschr(0.0, ts.scale);
        const double title_h = L.title.empty() ? 0.0 : 2.2 * ts.px / L.height;
        if (!L.title.empty()) DrawPageTitle(L.title, title_h, ts);
        const double cell_w = 1.0 / columns, cell_h = (1.0 - title_h) / rows;
        for (size_t k = 0; k < panels.size(); ++k) {
          const PlotOptions& o = panels[k].axes;
          const int r = static_cast<int>(k) / columns, c = static_cast<int>(k) % columns;
          const double x0 = c * cell_w, y1 = 1.0 - title_h - r * cell_h;
          double right = x0 + cell_w - 1.6 * ts.px / L.width;
          if (o.legend == LegendPosition::kOutsideRight) {
            std::vector<std::string> labels;
            for (const PlotSeries& s : panels[k].series) labels.push_back(s.label);
            right -= internal::OutsideLegendWidth(labels, ts, L.width,
                                                  right - x0 - 6.4 * ts.px / L.width);
          }
          const Box vp{x0 + 6.4 * ts.px / L.width, right, y1 - cell_h + 4.6 * ts.px / L.height,
                       y1 - (o.title.empty() ? 1.2 : 2.6) * ts.px / L.height};
          internal::DrawSeriesPanel(panels[k].series, o, vp, ts, L.width, L.height,
                                    kFirstSeriesSlot + first[k], kFirstSeriesSlot + n + first[k]);
        }
      },
      image, bytes);
}

}  // namespace

std::array<std::uint8_t, 3> SeriesColor(int i) {
  return kTab10[static_cast<size_t>(((i % 10) + 10) % 10)];
}

Image RenderPlot(const std::vector<PlotSeries>& series, const PlotOptions& o) {
  Image image;
  DrawPlot(series, o, FigureFormat::kPng, &image, nullptr);
  return image;
}

Figure PlotFigure(const std::vector<PlotSeries>& series, const PlotOptions& options) {
  return internal::PlplotFigure(
      [series, options](FigureFormat f, Image* image, std::string* bytes) {
        DrawPlot(series, options, f, image, bytes);
      });
}

Figure PanelsFigure(const std::vector<PlotPanel>& panels, const PanelLayout& layout) {
  return internal::PlplotFigure([panels, layout](FigureFormat f, Image* image, std::string* bytes) {
    DrawPanels(panels, layout, f, image, bytes);
  });
}

}  // namespace render
