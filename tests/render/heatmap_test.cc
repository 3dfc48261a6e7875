// Colormaps and heatmap figures, checked numerically (render/heatmap.h).
#include "render/heatmap.h"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <set>

namespace render {
namespace {

using Rgb = std::array<std::uint8_t, 3>;

Rgb Pixel(const Image& img, int x, int y) {
  const std::uint8_t* p = img.at(x, y);
  return {p[0], p[1], p[2]};
}

TEST(ColormapTest, DivergingEndsAndCentre) {
  EXPECT_EQ(DivergingColor(-1.0), (Rgb{5, 48, 97}));      // dark blue
  EXPECT_EQ(DivergingColor(0.0), (Rgb{247, 247, 247}));   // near white
  EXPECT_EQ(DivergingColor(1.0), (Rgb{103, 0, 31}));      // dark red
  EXPECT_EQ(DivergingColor(-5.0), DivergingColor(-1.0));  // clamped
  // Symmetric lightness: +t and -t are equally far from the white centre in luminance.
  for (double t : {0.25, 0.5, 0.75}) {
    const Rgb pos = DivergingColor(t), neg = DivergingColor(-t);
    const double lp = 0.299 * pos[0] + 0.587 * pos[1] + 0.114 * pos[2];
    const double ln = 0.299 * neg[0] + 0.587 * neg[1] + 0.114 * neg[2];
    EXPECT_NEAR(lp, ln, 25.0) << t;
    EXPECT_GT(pos[0], pos[2]) << "positive is red";
    EXPECT_GT(neg[2], neg[0]) << "negative is blue";
  }
}

TEST(ColormapTest, ViridisEnds) {
  EXPECT_EQ(ViridisColor(0.0), (Rgb{68, 1, 84}));
  EXPECT_EQ(ViridisColor(1.0), (Rgb{253, 231, 37}));
  EXPECT_EQ(ViridisColor(0.5), (Rgb{33, 145, 140}));
}

TEST(HeatmapTest, CellsAreWholePixelsWithTheRightColours) {
  Eigen::MatrixXd m(2, 3);
  m << -1.0, 0.0, 1.0,  //
      0.5, -0.5, 0.25;
  HeatmapOptions o;
  o.width = 320;
  o.height = 240;
  o.title = "test";
  const Image img = RenderHeatmap(m, o);
  const HeatmapLayout L = ComputeHeatmapLayout(2, 3, o);
  ASSERT_EQ(img.width, L.width);
  ASSERT_LE(img.width, 320);
  // Square cells of equal integer size.
  const int cell = L.col_edges[1] - L.col_edges[0];
  EXPECT_GT(cell, 10);
  for (int j = 0; j < 3; ++j) EXPECT_EQ(L.col_edges[j + 1] - L.col_edges[j], cell);
  for (int i = 0; i < 2; ++i) EXPECT_EQ(L.row_edges[i + 1] - L.row_edges[i], cell);
  // Every pixel of every cell has exactly the colour of its value (limit = max |v| = 1).
  for (int i = 0; i < 2; ++i) {
    for (int j = 0; j < 3; ++j) {
      const Rgb want = DivergingColor(m(i, j));
      for (int y = L.row_edges[i]; y < L.row_edges[i + 1]; ++y) {
        for (int x = L.col_edges[j]; x < L.col_edges[j + 1]; ++x) {
          ASSERT_EQ(Pixel(img, x, y), want)
              << "cell " << i << "," << j << " pixel " << x << "," << y;
        }
      }
    }
  }
  // Row 0 is on top, column 0 on the left.
  EXPECT_LT(L.row_edges[0], L.row_edges[1]);
  // Colour bar: +limit at the top (red), -limit at the bottom (blue).
  const int bx = L.bar_x + L.bar_w / 2;
  EXPECT_EQ(Pixel(img, bx, L.bar_y), DivergingColor(1.0 - 1.0 / L.bar_h));
  EXPECT_EQ(Pixel(img, bx, L.bar_y + L.bar_h - 1), DivergingColor(-1.0 + 1.0 / L.bar_h));
}

TEST(HeatmapTest, LimitsAreSymmetricAboutZero) {
  Eigen::MatrixXd m(1, 2);
  m << -0.2, 0.5;  // limit 0.5 on both sides: -0.2 maps to t = -0.4, not to the blue end
  HeatmapOptions o;
  const Image img = RenderHeatmap(m, o);
  const HeatmapLayout L = ComputeHeatmapLayout(1, 2, o);
  const int y = (L.row_edges[0] + L.row_edges[1]) / 2;
  EXPECT_EQ(Pixel(img, (L.col_edges[0] + L.col_edges[1]) / 2, y), DivergingColor(-0.4));
  EXPECT_EQ(Pixel(img, (L.col_edges[1] + L.col_edges[2]) / 2, y), DivergingColor(1.0));
}

TEST(HeatmapTest, UnsignedDataUsesViridis) {
  Eigen::MatrixXd m(1, 2);
  m << 0.0, 2.0;
  HeatmapOptions o;
  const Image img = RenderHeatmap(m, o);
  const HeatmapLayout L = ComputeHeatmapLayout(1, 2, o);
  const int y = (L.row_edges[0] + L.row_edges[1]) / 2;
  EXPECT_EQ(Pixel(img, (L.col_edges[0] + L.col_edges[1]) / 2, y), ViridisColor(0.0));
  EXPECT_EQ(Pixel(img, (L.col_edges[1] + L.col_edges[2]) / 2, y), ViridisColor(1.0));
}

TEST(HeatmapTest, TextIsAntiAliasedGlyphsNotBlocks) {
  Eigen::MatrixXd m = Eigen::MatrixXd::Zero(4, 4);
  HeatmapOptions o;
  o.title = "Writhe";
  const Image img = RenderHeatmap(m, o);
  // The title band holds dark ink and intermediate greys (glyph edges).
  std::set<int> greys;
  int dark = 0;
  for (int y = 0; y < 30; ++y) {
    for (int x = 0; x < img.width; ++x) {
      const int v = img.at(x, y)[0];
      if (v < 80) ++dark;
      if (v > 80 && v < 220) greys.insert(v);
    }
  }
  EXPECT_GT(dark, 30);
  EXPECT_GT(greys.size(), 10u);
}

TEST(HeatmapTest, LargeMatricesStillSnapToPixels) {
  Eigen::MatrixXd m(300, 500);
  for (int i = 0; i < 300; ++i) {
    for (int j = 0; j < 500; ++j) m(i, j) = std::sin(0.1 * i + 0.07 * j);
  }
  HeatmapOptions o;
  o.width = 320;
  o.height = 240;
  const HeatmapLayout L = ComputeHeatmapLayout(300, 500, o);
  EXPECT_EQ(L.col_edges.front(), L.plot_x);
  EXPECT_EQ(L.col_edges.back(), L.plot_x + L.plot_w);
  const Image img = RenderHeatmap(m, o);
  EXPECT_EQ(img.width, L.width);
  EXPECT_LE(img.width, 320);
}

TEST(HeatmapTest, BadInput) {
  EXPECT_THROW(RenderHeatmap(Eigen::MatrixXd(0, 3), {}), std::invalid_argument);
  HeatmapOptions tiny;
  tiny.width = 50;
  EXPECT_THROW(RenderHeatmap(Eigen::MatrixXd::Zero(2, 2), tiny), std::invalid_argument);
}

}  // namespace
}  // namespace render
