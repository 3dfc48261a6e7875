// Figure helpers shared by everything that draws (the render, heatmap, writhe --heatmap, plan,
// bench, grasp and demo commands, the viewer, Python): image sizes, vector formats of a figure, and
// the writhe heatmap figure.
#pragma once

#include <Eigen/Core>
#include <string>
#include <vector>

#include "render/figure.h"
#include "render/image.h"

namespace visualize {

// Parses "WxH" (e.g. "640x480") into *width, *height in [16, 8192]. Throws
// std::invalid_argument naming `flag` otherwise.
void ParseImageSize(const std::string& text, const std::string& flag, int* width, int* height);

// Writes the SVG/PDF versions of a figure whose PNG is (or will be) `png_path`: one file per
// non-PNG entry of `formats`, the extension replaced (plots/fig.png -> plots/fig.svg). PNG is
// written by the caller (pages, contact sheets and goldens use it). Returns the paths written.
std::vector<std::string> WriteVectorFormats(const std::string& png_path,
                                            const render::Figure& figure,
                                            const std::vector<render::FigureFormat>& formats);

struct WritheFigureOptions {
  int width = 640;  // largest size; the canvas follows the matrix's aspect
  int height = 480;
  // Empty: "Writhe matrix <a_name> × <b_name> (total <sum>)".
  std::string title;
  // Diverging colours symmetric about 0 for the signed writhe (whatever the signs present);
  // sequential viridis for the unsigned solid-angle variant.
  bool signed_values = true;
  // Axis captions; empty: "Segment of <a_name>" (rows) and "Segment of <b_name>" (columns).
  std::string row_label, col_label;
  // Colour limit (one for a whole sequence, or --clim); <= 0: this matrix's max |value|.
  double limit = 0.0;
  bool mark_peak = false;  // outline the largest |entry| and name it under the axis
  // Segments per cell of a block-summed matrix (topology::BlockWritheSums): ticks count segments,
  // the colour bar reads "Summed writhe" and the default title says "Block-summed writhe".
  int row_block = 1, col_block = 1;
};

// The writhe-matrix heatmap figure (any format): rows = segments of chain A named `a_name`,
// columns = segments of B.
render::Figure WritheFigure(const Eigen::MatrixXd& w, const std::string& a_name,
                            const std::string& b_name, const WritheFigureOptions& options);

// WritheFigure(...).Raster() with the default options but size, title and signedness.
render::Image WritheHeatmapFigure(const Eigen::MatrixXd& w, const std::string& a_name,
                                  const std::string& b_name, int width, int height,
                                  const std::string& title = "", bool signed_values = true);

}  // namespace visualize
