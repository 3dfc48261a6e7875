// Figure formats: SVG (parsed as XML, one <rect class="cell"> per matrix entry, real <text>),
// PDF (one page), shared colour ranges of a sequence, heatmap aspect and typography
// (render/figure.h, heatmap.h, plot.h; app::PlanHeatmapLimit).
#include "render/figure.h"

#include <gtest/gtest.h>
#include <tinyxml.h>

#include <cmath>
#include <regex>
#include <string>
#include <vector>

#include "app/present/reports.h"
#include "render/heatmap.h"
#include "render/plot.h"

namespace render {
namespace {

// Parses `svg` as XML; returns the root element (fails the test when it is not XML).
struct Svg {
  TiXmlDocument doc;
  explicit Svg(const std::string& text) {
    doc.Parse(text.c_str());
    EXPECT_FALSE(doc.Error()) << doc.ErrorDesc() << " at row " << doc.ErrorRow();
  }
  // Elements named `name` anywhere below the root, with class `cls` when given.
  std::vector<const TiXmlElement*> Find(const char* name, const char* cls = nullptr) const {
    std::vector<const TiXmlElement*> out;
    Collect(doc.RootElement(), name, cls, &out);
    return out;
  }
  std::vector<std::string> Texts() const {
    std::vector<std::string> out;
    for (const TiXmlElement* e : Find("text")) out.push_back(e->GetText() ? e->GetText() : "");
    return out;
  }

 private:
  static void Collect(const TiXmlElement* e, const char* name, const char* cls,
                      std::vector<const TiXmlElement*>* out) {
    if (!e) return;
    if (std::string(e->Value()) == name &&
        (!cls || (e->Attribute("class") && std::string(e->Attribute("class")) == cls))) {
      out->push_back(e);
    }
    for (const TiXmlElement* c = e->FirstChildElement(); c; c = c->NextSiblingElement()) {
      Collect(c, name, cls, out);
    }
  }
};

// Number of pages of a PDF: "/Type /Page" objects (not "/Pages").
int PdfPages(const std::string& pdf) {
  static const std::regex kPage(R"(/Type\s*/Page[^s])");
  return static_cast<int>(
      std::distance(std::sregex_iterator(pdf.begin(), pdf.end(), kPage), std::sregex_iterator()));
}

Eigen::MatrixXd Wave(int rows, int cols, double scale) {
  Eigen::MatrixXd m(rows, cols);
  for (int i = 0; i < rows; ++i) {
    for (int j = 0; j < cols; ++j) m(i, j) = scale * std::sin(0.7 * i - 0.4 * j + 0.3);
  }
  return m;
}

TEST(FigureFormatTest, NamesPathsAndLists) {
  EXPECT_EQ(FigureFormatForPath("out/fig.svg", "-o"), FigureFormat::kSvg);
  EXPECT_EQ(FigureFormatForPath("fig.PDF", "-o"), FigureFormat::kPdf);
  EXPECT_EQ(FigureFormatForPath("fig.png", "-o"), FigureFormat::kPng);
  EXPECT_THROW(FigureFormatForPath("fig.jpg", "-o"), std::invalid_argument);
  EXPECT_THROW(FigureFormatForPath("fig", "-o"), std::invalid_argument);
  EXPECT_EQ(
      ParseFigureFormats("png,svg,pdf,svg", "--formats"),
      (std::vector<FigureFormat>{FigureFormat::kPng, FigureFormat::kSvg, FigureFormat::kPdf}));
  EXPECT_THROW(ParseFigureFormats("png,eps", "--formats"), std::invalid_argument);
  EXPECT_THROW(ParseFigureFormats("", "--formats"), std::invalid_argument);
  EXPECT_EQ(PathWithFormat("a/b/unwrap.png", FigureFormat::kPdf), "a/b/unwrap.pdf");
}

TEST(FigureFormatTest, NumbersUseOneMinusSignAndNoNegativeZero) {
  EXPECT_EQ(FormatNumber(-0.0004, 3), "0.000");
  EXPECT_EQ(FormatNumber(-0.0, 2), "0.00");
  EXPECT_EQ(FormatNumber(-0.0004, 3, true), "0.000");
  EXPECT_EQ(FormatNumber(-1.25, 2), "\u22121.25");
  EXPECT_EQ(FormatNumber(0.5, 1, true), "+0.5");
  EXPECT_EQ(FormatNumber(3.0, 0), "3");
}

TEST(HeatmapFigureTest, SvgHasOneRectPerCellAndRealText) {
  const Eigen::MatrixXd m = Wave(5, 7, 0.3);
  HeatmapOptions o;
  o.title = "Test \u00d7 <chains> & more";
  o.row_label = "Arm segment";
  o.col_label = "Pole segment";
  const std::string svg = HeatmapFigure(m, o).Encode(FigureFormat::kSvg);
  const Svg doc(svg);
  EXPECT_EQ(doc.Find("rect", "cell").size(), 35u);
  EXPECT_GT(doc.Find("rect", "bar").size(), 50u);
  const std::vector<std::string> texts = doc.Texts();
  auto has = [&](const std::string& t) {
    return std::find(texts.begin(), texts.end(), t) != texts.end();
  };
  EXPECT_TRUE(has("Arm segment"));
  EXPECT_TRUE(has("Pole segment"));
  EXPECT_TRUE(has("Test \u00d7 <chains> & more"));  // escaped in the file, intact when parsed
  bool minus = false;
  for (const std::string& t : texts) {
    EXPECT_EQ(t.find('-'), std::string::npos) << "ASCII hyphen as minus in '" << t << "'";
    minus |= t.find("\u2212") != std::string::npos;
  }
  EXPECT_TRUE(minus) << "negative colour-bar ticks carry U+2212";
  // Same canvas as the PNG.
  const Image png = HeatmapFigure(m, o).Raster();
  const TiXmlElement* root = doc.doc.RootElement();
  EXPECT_EQ(root->Attribute("width"), std::to_string(png.width));
  EXPECT_EQ(root->Attribute("height"), std::to_string(png.height));
}

TEST(HeatmapFigureTest, PdfIsOnePageAndReproducible) {
  const Eigen::MatrixXd m = Wave(4, 9, 1.0);
  HeatmapOptions o;
  o.title = "PDF";
  const std::string pdf = HeatmapFigure(m, o).Encode(FigureFormat::kPdf);
  ASSERT_GT(pdf.size(), 100u);
  EXPECT_EQ(pdf.substr(0, 4), "%PDF");
  EXPECT_EQ(PdfPages(pdf), 1);
  EXPECT_EQ(pdf, HeatmapFigure(m, o).Encode(FigureFormat::kPdf));
}

TEST(HeatmapFigureTest, FramesOfOneSequenceShareTheColourBar) {
  // The second frame has a tenth of the first one's writhe: with one sequence limit its colour
  // bar still reads ±the first frame's peak.
  const std::vector<Eigen::MatrixXd> frames = {Wave(6, 4, 0.15), Wave(6, 4, 0.015)};
  const double limit = visualize::PlanHeatmapLimit(frames);
  EXPECT_NEAR(limit, frames[0].cwiseAbs().maxCoeff(), 1e-15);
  EXPECT_EQ(visualize::PlanHeatmapLimit(frames, 0.5), 0.5);  // --clim wins
  auto bar_labels = [](const Eigen::MatrixXd& m, double lim) {
    HeatmapOptions o;
    o.limit = lim;
    o.title = "same title";
    return Svg(HeatmapFigure(m, o).Encode(FigureFormat::kSvg)).Texts();
  };
  EXPECT_EQ(bar_labels(frames[0], limit), bar_labels(frames[1], limit));
  EXPECT_NE(bar_labels(frames[0], 0.0), bar_labels(frames[1], 0.0));  // per-frame limits differ
  // The same colours in PNG: the second frame's cells are pale (|t| <= 0.1).
  HeatmapOptions o;
  o.limit = limit;
  const Image img = RenderHeatmap(frames[1], o);
  const HeatmapLayout L = ComputeHeatmapLayout(6, 4, o);
  const std::uint8_t* p = img.at(L.col_edges[0] + 1, L.row_edges[0] + 1);
  EXPECT_EQ((std::array<std::uint8_t, 3>{p[0], p[1], p[2]}),
            DivergingColor(frames[1](0, 0) / limit));
}

TEST(HeatmapFigureTest, CanvasFollowsTheMatrix) {
  HeatmapOptions o;
  o.title = "Strip";
  const HeatmapLayout tall = ComputeHeatmapLayout(20, 1, o);
  EXPECT_LT(tall.width, tall.height);
  EXPECT_LE(tall.width, 400);
  const HeatmapLayout flat = ComputeHeatmapLayout(3, 24, o);
  EXPECT_LT(flat.height, 360);
  EXPECT_GE(flat.width, 600);
  const HeatmapLayout square = ComputeHeatmapLayout(64, 64, o);
  EXPECT_LT(square.width, 640);
  // Little white space: the matrix and colour bar fill the canvas but for the margins.
  for (const HeatmapLayout* L : {&tall, &flat, &square}) {
    EXPECT_GE(L->plot_x, 20);
    EXPECT_LE(L->width - (L->bar_x + L->bar_w), 100);  // tick labels and caption only
    EXPECT_EQ(RenderHeatmap(Eigen::MatrixXd::Ones(static_cast<int>(L->row_edges.size()) - 1,
                                                  static_cast<int>(L->col_edges.size()) - 1),
                            o)
                  .width,
              L->width);
  }
  o.fit_to_matrix = false;
  EXPECT_EQ(ComputeHeatmapLayout(20, 1, o).width, 640);
}

TEST(HeatmapFigureTest, PeakMarkerNamesTheLargestEntry) {
  Eigen::MatrixXd m = Eigen::MatrixXd::Constant(4, 3, 0.01);
  m(2, 1) = -0.4;
  HeatmapOptions o;
  o.mark_peak = true;
  const Svg doc(HeatmapFigure(m, o).Encode(FigureFormat::kSvg));
  const std::vector<std::string> texts = doc.Texts();
  EXPECT_NE(std::find(texts.begin(), texts.end(), "Peak (outlined): row 2, column 1 (\u22120.400)"),
            texts.end());
  // The outline is drawn around the cell in the PNG: dark pixels just outside its corner.
  const Image img = RenderHeatmap(m, o);
  const HeatmapLayout L = ComputeHeatmapLayout(4, 3, o);
  const std::uint8_t* p = img.at(L.col_edges[1] - 3, L.row_edges[2] - 3);
  EXPECT_LT(p[0], 80);
}

std::vector<PlotSeries> TwoSeries() {
  PlotSeries a("AICO", {0, 90, 180, 270}, {200, 230, 260, 300});
  a.y_lo = {180, 200, 240, 280};
  a.y_hi = {220, 260, 280, 330};
  PlotSeries b("RRT", {0, 90, 180, 270}, {900, 2000, 5000, NAN});
  b.failure_x = {270};
  b.failure_y = {1e5};
  return {a, b};
}

TEST(PlotFigureTest, SvgAndPdfThroughPlplotCairo) {
  PlotOptions o;
  o.title = "Checks";
  o.x_label = "Angle to unwrap (deg)";
  o.y_label = "Collision checks";
  o.log_y = true;
  const Figure f = PlotFigure(TwoSeries(), o);
  const std::string svg = f.Encode(FigureFormat::kSvg);
  const Svg doc(svg);
  ASSERT_NE(doc.doc.RootElement(), nullptr);
  EXPECT_EQ(std::string(doc.doc.RootElement()->Value()), "svg");
  const std::string pdf = f.Encode(FigureFormat::kPdf);
  EXPECT_EQ(pdf.substr(0, 4), "%PDF");
  EXPECT_EQ(PdfPages(pdf), 1);
  EXPECT_TRUE(SameImage(f.Raster(), RenderPlot(TwoSeries(), o)));
}

TEST(PlotFigureTest, PanelsShareOnePage) {
  PlotPanel p1{TwoSeries(), {}}, p2{TwoSeries(), {}}, p3{TwoSeries(), {}};
  p1.axes.log_y = p2.axes.log_y = p3.axes.log_y = true;
  p2.axes.legend = p3.axes.legend = LegendPosition::kNone;
  PanelLayout layout;
  layout.width = 900;
  layout.height = 320;
  layout.columns = 3;
  layout.title = "Three panels";
  const Figure f = PanelsFigure({p1, p2, p3}, layout);
  const std::string pdf = f.Encode(FigureFormat::kPdf);
  EXPECT_EQ(pdf.substr(0, 4), "%PDF");
  EXPECT_EQ(PdfPages(pdf), 1);
  const Image a = f.Raster(), b = f.Raster();
  EXPECT_EQ(a.width, 900);
  EXPECT_TRUE(SameImage(a, b));  // deterministic
  EXPECT_THROW(PanelsFigure({}, layout).Raster(), std::invalid_argument);
  PlotPanel bad;
  bad.series = {PlotSeries("x", {1, 2}, {1})};
  EXPECT_THROW(PanelsFigure({bad}, layout).Raster(), std::invalid_argument);
  bad.series = {PlotSeries("x", {1, 2}, {1, 2})};
  bad.series[0].y_lo = {1};
  bad.series[0].y_hi = {1};
  EXPECT_THROW(PanelsFigure({bad}, layout).Raster(), std::invalid_argument);
}

TEST(PlotFigureTest, GroupedBarsWithWhiskers) {
  BarChart chart;
  chart.categories = {"power_bottle", "lateral_pinch_box", "ring_grip_torus"};
  BarSeries a, b;
  a.label = "winding";
  a.values = {1.0, 0.5, 0.0};
  a.lo = {0.8, 0.3, NAN};
  a.hi = {1.0, 0.7, NAN};
  b.label = "joint";
  b.values = {0.2, NAN, 1.0};
  chart.series = {a, b};
  PlotOptions o;
  o.width = 640;
  o.height = 400;
  o.y_label = "Stable fraction";
  o.y_min = 0.0;
  o.y_max = 1.0;
  o.legend = LegendPosition::kOutsideRight;
  const Figure f = BarChartFigure(chart, o);
  const Image img = f.Raster();
  EXPECT_EQ(img.width, 640);
  // Bars in both tab10 colours are present.
  int blue = 0, orange = 0;
  for (size_t i = 0; i < img.rgba.size(); i += 4) {
    const auto c = std::array<std::uint8_t, 3>{img.rgba[i], img.rgba[i + 1], img.rgba[i + 2]};
    blue += c == SeriesColor(0);
    orange += c == SeriesColor(1);
  }
  EXPECT_GT(blue, 500);
  EXPECT_GT(orange, 500);
  EXPECT_EQ(PdfPages(f.Encode(FigureFormat::kPdf)), 1);
  Svg doc(f.Encode(FigureFormat::kSvg));
  EXPECT_NE(doc.doc.RootElement(), nullptr);
  chart.series[1].values = {1.0};
  EXPECT_THROW(BarChartFigure(chart, o).Raster(), std::invalid_argument);
}

}  // namespace
}  // namespace render
