// The ablation panels of `bench unwrap --ablation` (visualize/unwrap_figures.h): what each series
// holds and where it is drawn.
#include "visualize/unwrap_figures.h"

#include <gtest/gtest.h>

#include <stdexcept>
#include <string>
#include <vector>

#include "planning/motion/unwrap_benchmark.h"

namespace visualize {
namespace {

// Three variants over 540° and 720°, one seed each: every run solved except "no-writhe" at 720°;
// variant v ends with |writhe| 0.01·(v + 1) and a reach error of 0.1 m at 540°, 0.2 m at 720°.
planning::UnwrapBenchmarkResult Result(const std::vector<planning::UnwrapAblation>& variants) {
  planning::UnwrapBenchmarkResult result;
  result.angles_deg = {540.0, 720.0};
  result.seeds = 1;
  for (double angle : result.angles_deg) {
    for (size_t v = 0; v < variants.size(); ++v) {
      planning::UnwrapRun run;
      run.angle_deg = angle;
      run.variant = variants[v].name;
      run.report.success = !(variants[v].name == "no-writhe" && angle == 720.0);
      run.report.final_writhe_total = -0.01 * static_cast<double>(v + 1);
      run.report.reach_error_m = angle == 540.0 ? 0.1 : 0.2;
      result.runs.push_back(run);
    }
  }
  return result;
}

TEST(UnwrapAblationPanels, SeriesAreDodgedAroundTheirAngleSoEqualValuesStayVisible) {
  const std::vector<planning::UnwrapAblation> variants = {{"full", {}, false, false},
                                                          {"no-writhe", {"writhe"}, false, false},
                                                          {"no-retry", {}, false, true}};
  const std::vector<render::PlotPanel> panels = UnwrapAblationPanels(Result(variants), variants);
  ASSERT_EQ(panels.size(), 3u);
  // Step 180°, K = 3: δ = 0.4·180 / 2 = 36°, offsets −36°, 0°, +36°.
  const std::vector<double> shift = {-36.0, 0.0, 36.0};
  for (const render::PlotPanel& panel : panels) {
    ASSERT_EQ(panel.series.size(), 3u);
    for (size_t v = 0; v < 3; ++v) {
      const render::PlotSeries& s = panel.series[v];
      EXPECT_EQ(s.label, variants[v].name);
      ASSERT_EQ(s.x.size(), 2u);
      EXPECT_DOUBLE_EQ(s.x[0], 540.0 + shift[v]);
      EXPECT_DOUBLE_EQ(s.x[1], 720.0 + shift[v]);
    }
  }
  // Success fraction, median |writhe|, median reach error.
  EXPECT_EQ(panels[0].series[0].y, (std::vector<double>{1.0, 1.0}));
  EXPECT_EQ(panels[0].series[1].y, (std::vector<double>{1.0, 0.0}));
  EXPECT_DOUBLE_EQ(panels[1].series[2].y[0], 0.03);
  EXPECT_DOUBLE_EQ(panels[2].series[1].y[1], 0.2);
}

TEST(UnwrapAblationPanels, OneAngleOrOneVariant) {
  const std::vector<planning::UnwrapAblation> two = {{"full", {}, false, false},
                                                     {"no-retry", {}, false, true}};
  planning::UnwrapBenchmarkResult result = Result(two);
  result.angles_deg = {540.0};
  std::erase_if(result.runs, [](const planning::UnwrapRun& r) { return r.angle_deg != 540.0; });
  // One angle: the step is taken as 90°, δ = 0.4·90 = 36°.
  std::vector<render::PlotPanel> panels = UnwrapAblationPanels(result, two);
  EXPECT_DOUBLE_EQ(panels[0].series[0].x[0], 540.0 - 18.0);
  EXPECT_DOUBLE_EQ(panels[0].series[1].x[0], 540.0 + 18.0);
  // One variant: not moved.
  const std::vector<planning::UnwrapAblation> one = {{"full", {}, false, false}};
  panels = UnwrapAblationPanels(Result(one), one);
  EXPECT_EQ(panels[0].series[0].x, (std::vector<double>{540.0, 720.0}));
  EXPECT_THROW(UnwrapAblationPanels(planning::UnwrapBenchmarkResult{}, one), std::invalid_argument);
}

}  // namespace
}  // namespace visualize
