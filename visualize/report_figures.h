// Figures of planning and grasp results (render::Figure, any format): writhe heatmaps of a plan,
// writhe and cost over time, Fig. 4.5 of the unwrap benchmark, the grasp summary bars.
#pragma once

#include <Eigen/Core>
#include <optional>
#include <string>
#include <vector>

#include "planning/motion/scenario.h"
#include "planning/motion/unwrap_benchmark.h"
#include "planning/physics/grasp_trials.h"
#include "render/figure.h"

namespace visualize {

// The colour limit of a heatmap sequence: `clim` when > 0, else the largest |entry| over all
// matrices (render::SequenceLimit): symmetric, the same for every frame.
double PlanHeatmapLimit(const std::vector<Eigen::MatrixXd>& matrices, double clim = 0.0);

// The writhe heatmap of the report pair at time `time_s` of a plan: rows "<Chain> segment",
// columns "<Object> segment" (names from the scenario's writhe_report), colour limit `limit`,
// title "Writhe matrix at t = <time> s (total <sum>)".
render::Figure PlanHeatmapFigure(const planning::Scenario& scenario, const Eigen::MatrixXd& w,
                                 double time_s, double limit);

// Total writhe (turns) and task cost over time (s) on two panels sharing the time axis.
render::Figure WritheCostFigure(const std::string& scenario_name, const std::vector<double>& time_s,
                                const std::vector<double>& writhe, const std::vector<double>& cost);

// unwrap.png (Fig. 4.5): three panels over the angle to unwrap, log y: collision checks,
// narrow-phase calls and wall time. Per planner (one colour each, result order): the median over
// the seeds' successful runs, an interquartile band when an angle has at least two, and a cross
// at each failed run's value. Legend: in the first panel for up to six planners (1380 × 480 px),
// else right of the last panel (1700 × 480 px). Empty when there is nothing to draw (no run at all).
std::optional<render::Figure> UnwrapFigure(const planning::UnwrapBenchmarkResult& result);

// Input of the grasp summary figure: one group of bars per grasp, one bar (colour) per method,
// with an optional interval [lo, hi] per bar, e.g. a 95% confidence interval over perturbed
// trials. value[m][g] is method m on grasp g; lo and hi are empty or have value's shape (NaN:
// no whisker on that bar).
struct GraspSummaryData {
  std::string title;
  std::string y_label;
  double y_max = 1.0;  // top of the value axis
  std::vector<std::string> grasps, methods;
  std::vector<std::vector<double>> value, lo, hi;
};

// The summary figure's data: without perturbations, gravity directions held out of 6 per grasp
// and method (no whiskers); with --perturb N, the stable fraction of the N perturbed repetitions
// with its Wilson 95 % interval as whiskers. Method names carry their stable count ("winding
// (3/8 stable)").
GraspSummaryData GraspSummaryDataOf(const planning::physics::GraspTrialsResult& result);

// summary.png: grouped bars, grasp names on the x axis, legend of methods at the right.
render::Figure GraspSummaryFigure(const GraspSummaryData& data);

}  // namespace visualize
