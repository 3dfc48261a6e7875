// PLplot-based plots (render/plot.h): they draw, they are deterministic, bad input throws.
#include "render/plot.h"

#include <gtest/gtest.h>

#include <cmath>

namespace render {
namespace {

PlotSeries Series(const std::string& label, std::vector<double> x = {},
                  std::vector<double> y = {}) {
  PlotSeries s;
  s.label = label;
  s.x = std::move(x);
  s.y = std::move(y);
  return s;
}

std::vector<PlotSeries> UnwrapLikeData() {
  PlotSeries aico = Series("AICO"), birrt = Series("BiRRT");
  birrt.marker = Marker::kSquare;
  for (int k = 0; k <= 8; ++k) {
    const double angle = 90.0 * k;
    aico.x.push_back(angle);
    aico.y.push_back(100.0 + 40.0 * k * k);
    birrt.x.push_back(angle);
    birrt.y.push_back(1000.0 * std::exp(0.6 * k));
  }
  birrt.failure_x = {720.0};
  return {aico, birrt};
}

int CountColour(const Image& img, const std::array<std::uint8_t, 3>& rgb) {
  int n = 0;
  for (int y = 0; y < img.height; ++y) {
    for (int x = 0; x < img.width; ++x) {
      const std::uint8_t* p = img.at(x, y);
      n += p[0] == rgb[0] && p[1] == rgb[1] && p[2] == rgb[2];
    }
  }
  return n;
}

TEST(PlotTest, DrawsSeriesInTheirColoursDeterministically) {
  PlotOptions o;
  o.width = 320;
  o.height = 240;
  o.log_y = true;
  o.title = "checks";
  o.x_label = "angle";
  o.y_label = "collision checks";
  const Image a = RenderPlot(UnwrapLikeData(), o);
  const Image b = RenderPlot(UnwrapLikeData(), o);
  EXPECT_TRUE(SameImage(a, b));
  EXPECT_GT(CountColour(a, SeriesColor(0)), 50);
  EXPECT_GT(CountColour(a, SeriesColor(1)), 50);
  EXPECT_GT(CountColour(a, {255, 255, 255}), a.width * a.height / 2);
}

TEST(PlotTest, NonPositiveValuesAreSkippedOnLogAxes) {
  const PlotSeries s = Series("cost", {0, 1, 2, 3}, {10, 0, -1, 100});
  PlotOptions o;
  o.log_y = true;
  EXPECT_NO_THROW(RenderPlot({s}, o));
}

TEST(PlotTest, BadInput) {
  const PlotSeries bad = Series("x", {1, 2}, {1});
  EXPECT_THROW(RenderPlot({bad}, {}), std::invalid_argument);
  const PlotSeries empty = Series("e");
  EXPECT_THROW(RenderPlot({empty}, {}), std::invalid_argument);
  PlotOptions tiny;
  tiny.height = 20;
  EXPECT_THROW(RenderPlot(UnwrapLikeData(), tiny), std::invalid_argument);
}

}  // namespace
}  // namespace render
