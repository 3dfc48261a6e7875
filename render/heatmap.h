// Matrix heatmaps as publication-style figures (pure CPU, no GL context needed), and the
// colormaps they use.
//
// Layout: a title on top; the matrix with row 0 at the top (matrix convention) and column 0 on
// the left; cells snapped to whole pixels (square when the matrix fits, otherwise integer cell
// edges; a long thin matrix gets cells up to 4:1); integer index ticks on both axes with axis
// labels; a colour bar on the right with value ticks and a caption. The canvas shrinks to the
// matrix (a 20×1 matrix is a strip, not a square with white space). Text is DejaVu Sans
// (stb_truetype in PNG, <text> in SVG, embedded by cairo in PDF).
#pragma once

#include <Eigen/Core>
#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "render/figure.h"
#include "render/image.h"

namespace render {

// Diverging map for signed data (ColorBrewer RdBu, blue = negative, red = positive),
// interpolated linearly in sRGB between its 11 control colours. t in [-1, 1] (clamped):
// -1 -> (5,48,97) dark blue, 0 -> (247,247,247) near-white, +1 -> (103,0,31) dark red.
std::array<std::uint8_t, 3> DivergingColor(double t);

// Viridis for unsigned data, t in [0, 1] (clamped), interpolated between 9 samples of
// matplotlib's viridis: 0 -> (68,1,84), 1 -> (253,231,37).
std::array<std::uint8_t, 3> ViridisColor(double t);

enum class ColorScale {
  kAuto,        // diverging when any value is negative, else sequential
  kDiverging,   // limits [-L, L] symmetric about 0 (DivergingColor)
  kSequential,  // limits [0, L] (ViridisColor); for magnitudes such as |writhe|
};

struct HeatmapOptions {
  // Figure size in pixels (>= 160 x 120); with fit_to_matrix the largest size, the canvas
  // shrinking to the matrix's aspect (never below 160 x 120 or the title's width).
  int width = 640;
  int height = 480;
  bool fit_to_matrix = true;
  std::string title;                  // drawn in bold above the matrix; empty: none
  std::string row_label = "Row";      // y axis caption, e.g. "Arm segment"
  std::string col_label = "Column";   // x axis caption, e.g. "Pole segment"
  std::string value_label = "Value";  // colour bar caption, e.g. "Writhe"
  ColorScale scale = ColorScale::kAuto;
  // Colour limit L; values beyond are clamped. <= 0: max |value| over finite entries (1 if all
  // are zero). A sequence of figures passes one limit (SequenceLimit) so its colours compare.
  double limit = 0.0;
  // Outline the cell of the largest |entry| and name it ("peak: row i, column j (v)") below.
  bool mark_peak = false;
  // Indices per cell: cell (i, j) covers rows [i·row_block, (i+1)·row_block) of the underlying
  // index (e.g. segments of a block-summed writhe matrix); ticks and the peak note show the first
  // index of a cell.
  int row_block = 1, col_block = 1;
};

// The colour limit of a sequence of matrices: max |value| over the finite entries of all of
// them (1 when all are zero or there are none).
double SequenceLimit(const std::vector<Eigen::MatrixXd>& matrices);

// Pixel geometry of a heatmap figure (all integers; cell edges are whole pixels).
struct HeatmapLayout {
  int width = 0, height = 0;                       // canvas size
  int plot_x = 0, plot_y = 0;                      // top-left pixel of cell (0, 0)
  int plot_w = 0, plot_h = 0;                      // matrix area in pixels
  int bar_x = 0, bar_y = 0, bar_w = 0, bar_h = 0;  // colour bar rectangle
  // Pixel edges of the cells: column j spans [col_edges[j], col_edges[j+1]), rows likewise
  // (absolute image coordinates, rows+1 / cols+1 entries).
  std::vector<int> col_edges, row_edges;
};

// Computes the layout for a rows x cols matrix. Throws std::invalid_argument for an empty matrix
// or a figure smaller than 160 x 120.
HeatmapLayout ComputeHeatmapLayout(int rows, int cols, const HeatmapOptions& options);

// Renders the figure. Non-finite entries are drawn grey. Throws std::invalid_argument as
// ComputeHeatmapLayout, and render::EnvironmentError when the DejaVu font is not installed.
Image RenderHeatmap(const Eigen::MatrixXd& values, const HeatmapOptions& options);

// The same figure in any format: PNG as RenderHeatmap; SVG with one <rect class="cell"> per
// matrix entry (row-major), one <rect class="bar"> per colour-bar pixel row and <text> labels;
// PDF (one page, cairo) with the same geometry. Throws as RenderHeatmap (when encoded).
Figure HeatmapFigure(const Eigen::MatrixXd& values, const HeatmapOptions& options);

}  // namespace render
