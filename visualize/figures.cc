// Figure helpers (see figures.h).
#include "visualize/figures.h"

#include <regex>
#include <stdexcept>

#include "base/numbers.h"
#include "render/heatmap.h"

namespace visualize {

void ParseImageSize(const std::string& text, const std::string& flag, int* width, int* height) {
  static const std::regex kSize(R"(([0-9]{1,5})x([0-9]{1,5}))");
  std::smatch m;
  if (!std::regex_match(text, m, kSize)) {
    throw std::invalid_argument(flag + ": expected WxH such as 640x480, got '" + text + "'");
  }
  const int w = static_cast<int>(*base::ParseInteger(m[1].str()));
  const int h = static_cast<int>(*base::ParseInteger(m[2].str()));
  if (w < 16 || h < 16 || w > 8192 || h > 8192) {
    throw std::invalid_argument(flag + ": each side must be in [16, 8192], got '" + text + "'");
  }
  *width = w;
  *height = h;
}

std::vector<std::string> WriteVectorFormats(const std::string& png_path,
                                            const render::Figure& figure,
                                            const std::vector<render::FigureFormat>& formats) {
  std::vector<render::FigureFormat> vector;
  for (render::FigureFormat f : formats) {
    if (f != render::FigureFormat::kPng) vector.push_back(f);
  }
  return render::WriteFigureFormats(png_path, figure, vector);
}

render::Figure WritheFigure(const Eigen::MatrixXd& w, const std::string& a_name,
                            const std::string& b_name, const WritheFigureOptions& f) {
  render::HeatmapOptions o;
  o.scale = f.signed_values ? render::ColorScale::kDiverging : render::ColorScale::kSequential;
  o.width = f.width;
  o.height = f.height;
  const bool blocked = f.row_block > 1 || f.col_block > 1;
  std::string title = blocked ? "Block-summed writhe " : "Writhe matrix ";
  title.append(a_name).append(" \u00d7 ").append(b_name).append(" (total ");
  title.append(render::FormatNumber(w.sum(), 3)).append(")");
  o.title = f.title.empty() ? title : f.title;
  o.row_label = f.row_label.empty() ? "Segment of " + a_name : f.row_label;
  o.col_label = f.col_label.empty() ? "Segment of " + b_name : f.col_label;
  if (!blocked) {
    o.value_label = f.signed_values ? "Writhe" : "Solid angle (rad)";
  } else {
    o.value_label = f.signed_values ? "Summed writhe" : "Summed solid angle (rad)";
    o.value_label.append(" per ").append(std::to_string(f.row_block)).append("\u00d7");
    o.value_label.append(std::to_string(f.col_block)).append(" block");
  }
  o.row_block = f.row_block;
  o.col_block = f.col_block;
  o.limit = f.limit;
  o.mark_peak = f.mark_peak;
  return render::HeatmapFigure(w, o);
}

render::Image WritheHeatmapFigure(const Eigen::MatrixXd& w, const std::string& a_name,
                                  const std::string& b_name, int width, int height,
                                  const std::string& title, bool signed_values) {
  WritheFigureOptions f;
  f.width = width;
  f.height = height;
  f.title = title;
  f.signed_values = signed_values;
  return WritheFigure(w, a_name, b_name, f).Raster();
}

}  // namespace visualize
