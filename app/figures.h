// Figure helpers shared by commands that draw (render, heatmap, writhe --heatmap, later plan and
// bench): image-size flags and the writhe heatmap figure.
#pragma once

#include <Eigen/Core>
#include <string>

#include "render/image.h"

namespace app {

// Parses "WxH" (e.g. "640x480") into *width, *height in [16, 8192]. Throws
// std::invalid_argument naming `flag` otherwise.
void ParseImageSize(const std::string& text, const std::string& flag, int* width, int* height);

// The writhe-matrix heatmap figure: diverging colours symmetric about 0 for the signed writhe
// (whatever the signs present), sequential viridis for the unsigned solid-angle variant
// (`signed_values` false), rows = segments of chain A named `a_name`, columns = segments of B.
// An empty title becomes "Writhe matrix <a_name> × <b_name> (total <sum>)".
render::Image WritheHeatmapFigure(const Eigen::MatrixXd& w, const std::string& a_name,
                                  const std::string& b_name, int width, int height,
                                  const std::string& title = "", bool signed_values = true);

}  // namespace app
