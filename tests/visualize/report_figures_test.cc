// Fig. 4.5's figure (visualize/report_figures.h UnwrapFigure): where its legend goes.
#include "visualize/report_figures.h"

#include <gtest/gtest.h>

#include <cstdint>
#include <vector>

#include "planning/motion/unwrap_benchmark.h"
#include "render/image.h"

namespace visualize {
namespace {

// A result of `planners` planners over 0°, 180° and 360°, one seed: every run solved with
// 10³–10⁴ checks and calls, 0.1 s.
planning::UnwrapBenchmarkResult Result(int planners) {
  planning::UnwrapBenchmarkResult result;
  result.angles_deg = {0.0, 180.0, 360.0};
  result.seeds = 1;
  for (int p = 0; p < planners; ++p) result.planners.push_back(static_cast<planning::Planner>(p));
  for (double angle : result.angles_deg) {
    for (int p = 0; p < planners; ++p) {
      planning::UnwrapRun run;
      run.angle_deg = angle;
      run.planner = result.planners[static_cast<size_t>(p)];
      run.report.success = true;
      run.report.collision_checks = 1000 + 20 * static_cast<long>(angle) + 100 * p;
      run.report.narrow_phase_calls = 4 * run.report.collision_checks;
      run.report.time_s = 0.1;
      result.runs.push_back(run);
    }
  }
  return result;
}

// Pixels darker than text anti-aliasing's lightest grey (grid lines are light grey) in the box
// [x0, x1) × [y0, y1).
int DarkPixels(const render::Image& image, int x0, int x1, int y0, int y1) {
  int n = 0;
  for (int y = y0; y < y1; ++y) {
    for (int x = x0; x < x1; ++x) {
      const std::uint8_t* px = image.at(x, y);
      n += px[0] < 128 && px[1] < 128 && px[2] < 128 ? 1 : 0;
    }
  }
  return n;
}

TEST(UnwrapFigure, LegendOfManyPlannersStandsRightOfTheLastPanel) {
  // Up to six planners: the legend in the first panel's headroom, the figure 1380 px wide.
  const render::Image few = UnwrapFigure(Result(3))->Raster();
  ASSERT_EQ(few.width, 1380);
  // Seven or more: the legend's column right of the last panel; the first panel's headroom is
  // empty and the figure is wider.
  const render::Image many = UnwrapFigure(Result(7))->Raster();
  ASSERT_EQ(many.width, 1700);
  ASSERT_EQ(few.height, many.height);
  // The first panel's top-left corner inside its frame (the legend's place with few planners).
  const int legend_x0 = 90, legend_x1 = 200, legend_y0 = 75,
            legend_y1 = 115;  // below the top ticks
  EXPECT_GT(DarkPixels(few, legend_x0, legend_x1, legend_y0, legend_y1), 50);
  EXPECT_EQ(DarkPixels(many, legend_x0, legend_x1, legend_y0, legend_y1), 0);
  // The rightmost 150 px between a third and two thirds of the height: the legend's text.
  const int h = many.height;
  EXPECT_GT(DarkPixels(many, many.width - 150, many.width, h / 3, 2 * h / 3), 200);
}

}  // namespace
}  // namespace visualize
