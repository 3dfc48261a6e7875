// Figure helpers (see figures.h).
#include "app/figures.h"

#include <cstdio>
#include <regex>
#include <stdexcept>

#include "render/heatmap.h"

namespace app {

void ParseImageSize(const std::string& text, const std::string& flag, int* width, int* height) {
  static const std::regex kSize(R"(([0-9]{1,5})x([0-9]{1,5}))");
  std::smatch m;
  if (!std::regex_match(text, m, kSize)) {
    throw std::invalid_argument(flag + ": expected WxH such as 640x480, got '" + text + "'");
  }
  const int w = std::stoi(m[1].str()), h = std::stoi(m[2].str());
  if (w < 16 || h < 16 || w > 8192 || h > 8192) {
    throw std::invalid_argument(flag + ": each side must be in [16, 8192], got '" + text + "'");
  }
  *width = w;
  *height = h;
}

render::Image WritheHeatmapFigure(const Eigen::MatrixXd& w, const std::string& a_name,
                                  const std::string& b_name, int width, int height,
                                  const std::string& title, bool signed_values) {
  render::HeatmapOptions o;
  o.scale = signed_values ? render::ColorScale::kDiverging : render::ColorScale::kSequential;
  o.width = width;
  o.height = height;
  if (title.empty()) {
    char total[64];
    std::snprintf(total, sizeof(total), "%.3f", w.sum());
    std::string t = total;
    if (!t.empty() && t[0] == '-') t = "\u2212" + t.substr(1);
    o.title = "Writhe matrix " + a_name + " \u00d7 " + b_name + " (total " + t + ")";
  } else {
    o.title = title;
  }
  o.row_label = "segment of " + a_name;
  o.col_label = "segment of " + b_name;
  o.value_label = signed_values ? "writhe" : "solid angle (rad)";
  return render::RenderHeatmap(w, o);
}

}  // namespace app
